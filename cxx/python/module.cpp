#include <pybind11/pybind11.h>

namespace hypercontact::python {
void declare_obstacle(pybind11::module_& m);
void declare_normal_penalty(pybind11::module_& m);
void declare_nodal_area(pybind11::module_& m);
void declare_contact_search(pybind11::module_& m);
void declare_contact_elements(pybind11::module_& m);
void declare_rigid_contact(pybind11::module_& m);
void declare_rigid_contact_friction(pybind11::module_& m);
void declare_surface_contact(pybind11::module_& m);
void declare_surface_contact_friction(pybind11::module_& m);
void declare_assembly(pybind11::module_& m);
}  // namespace hypercontact::python

PYBIND11_MODULE(_cpp, m) {
  m.doc() = "hypercontact C++ contact kernels (private; use the hypercontact package)";
  hypercontact::python::declare_obstacle(m);
  hypercontact::python::declare_normal_penalty(m);
  hypercontact::python::declare_nodal_area(m);
  hypercontact::python::declare_contact_search(m);
  hypercontact::python::declare_contact_elements(m);
  hypercontact::python::declare_rigid_contact(m);
  hypercontact::python::declare_rigid_contact_friction(m);
  hypercontact::python::declare_surface_contact(m);
  hypercontact::python::declare_surface_contact_friction(m);
  hypercontact::python::declare_assembly(m);
}
