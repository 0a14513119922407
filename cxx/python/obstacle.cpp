// Bindings of obstacle.hpp (Feature, ObstacleProjection, RigidPlane, RigidBox, RigidCylinder,
// RigidSphere, project).
#include <cmath>
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <hypercontact/obstacle.hpp>

#include "array.hpp"

namespace hypercontact::python {

void declare_obstacle(py::module_& m) {
  py::enum_<Feature>(m, "Feature", "Closest feature of an obstacle")
      .value("Face", Feature::Face)
      .value("Edge", Feature::Edge)
      .value("Vertex", Feature::Vertex);

  py::class_<ObstacleProjection>(m, "ObstacleProjection",
                                 "Closest-point projection of a slave point onto an obstacle")
      .def(py::init([](double gap, const RealArray& normal, const RealArray& dnormal_dx,
                       Feature feature) {
             check_shape(dnormal_dx, "dnormal_dx", {3, 3});
             return ObstacleProjection{
                 gap, as_vector3(normal, "normal"),
                 Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(dnormal_dx.data()),
                 feature};
           }),
           py::arg("gap"), py::arg("normal"), py::arg("dnormal_dx"), py::arg("feature"))
      .def_readonly("gap", &ObstacleProjection::gap, "signed distance: > 0 open, < 0 penetration")
      .def_readonly("normal", &ObstacleProjection::normal, "unit outward normal, = d gap / d x")
      .def_readonly("dnormal_dx", &ObstacleProjection::dnormal_dx, "d normal / d x (3, 3)")
      .def_readonly("feature", &ObstacleProjection::feature);

  py::class_<RigidPlane>(m, "RigidPlane", "Rigid half-space; normal points out of the obstacle")
      .def(py::init([](const RealArray& point, const RealArray& normal) {
             const Eigen::Vector3d n = as_vector3(normal, "normal");
             if (!(n.norm() > 0) || !n.allFinite())
               throw py::value_error("normal: must be a finite non-zero vector");
             return RigidPlane{as_vector3(point, "point"), n.normalized()};
           }),
           py::arg("point"), py::arg("normal"), "RigidPlane(point, normal); normal is normalised")
      .def_readonly("point", &RigidPlane::point)
      .def_readonly("normal", &RigidPlane::normal)
      .def("__repr__", [](const RigidPlane& p) {
        return py::str("RigidPlane(point={}, normal={})")
            .format(py::cast(p.point).attr("tolist")(), py::cast(p.normal).attr("tolist")());
      });

  py::class_<RigidBox>(m, "RigidBox",
                       "Rigid axis-aligned box occupying [lo, hi], its edges and corners rounded "
                       "with radius (0: sharp); blended: a rounding of continuous curvature")
      .def(py::init([](const RealArray& lo, const RealArray& hi, double radius, bool blended) {
             const RigidBox box{as_vector3(lo, "lo"), as_vector3(hi, "hi"), radius, blended};
             if (!(box.lo.array() < box.hi.array()).all())
               throw py::value_error("RigidBox: need lo < hi in every coordinate");
             if (!(radius >= 0) || !std::isfinite(radius) ||
                 !(2 * radius <= (1 + 1e-12) * (box.hi - box.lo).minCoeff()))
               throw py::value_error(
                   "RigidBox: need 0 <= radius <= half the shortest side (hi - lo)");
             return box;
           }),
           py::arg("lo"), py::arg("hi"), py::arg("radius") = 0.0, py::arg("blended") = false)
      .def_readonly("lo", &RigidBox::lo)
      .def_readonly("hi", &RigidBox::hi)
      .def_readonly("radius", &RigidBox::radius)
      .def_readonly("blended", &RigidBox::blended)
      .def("__repr__", [](const RigidBox& b) {
        return py::str("RigidBox(lo={}, hi={}, radius={}, blended={})")
            .format(py::cast(b.lo).attr("tolist")(), py::cast(b.hi).attr("tolist")(), b.radius,
                    b.blended);
      });

  py::class_<RigidCylinder>(m, "RigidCylinder",
                            "Rigid circular cylinder (infinite length); outside is admissible, or "
                            "inside with inside=True (a bore)")
      .def(py::init([](const RealArray& point, const RealArray& axis, double radius, bool inside) {
             const Eigen::Vector3d a = as_vector3(axis, "axis");
             if (!(a.norm() > 0) || !a.allFinite())
               throw py::value_error("axis: must be a finite non-zero vector");
             if (!(std::isfinite(radius) && radius > 0))
               throw py::value_error("radius: must be finite and > 0");
             return RigidCylinder{as_vector3(point, "point"), a.normalized(), radius, inside};
           }),
           py::arg("point"), py::arg("axis"), py::arg("radius"), py::arg("inside") = false,
           "RigidCylinder(point, axis, radius, inside=False); axis is normalised")
      .def_readonly("point", &RigidCylinder::point)
      .def_readonly("axis", &RigidCylinder::axis)
      .def_readonly("radius", &RigidCylinder::radius)
      .def_readonly("inside", &RigidCylinder::inside)
      .def("__repr__", [](const RigidCylinder& c) {
        return py::str("RigidCylinder(point={}, axis={}, radius={}, inside={})")
            .format(py::cast(c.point).attr("tolist")(), py::cast(c.axis).attr("tolist")(),
                    c.radius, c.inside);
      });

  py::class_<RigidSphere>(m, "RigidSphere", "Rigid ball; outside is admissible")
      .def(py::init([](const RealArray& center, double radius) {
             const Eigen::Vector3d c = as_vector3(center, "center");
             if (!c.allFinite()) throw py::value_error("center: must be finite");
             if (!(std::isfinite(radius) && radius > 0))
               throw py::value_error("radius: must be finite and > 0");
             return RigidSphere{c, radius};
           }),
           py::arg("center"), py::arg("radius"), "RigidSphere(center, radius)")
      .def_readonly("center", &RigidSphere::center)
      .def_readonly("radius", &RigidSphere::radius)
      .def("__repr__", [](const RigidSphere& s) {
        return py::str("RigidSphere(center={}, radius={})")
            .format(py::cast(s.center).attr("tolist")(), s.radius);
      });

  m.def(
      "project",
      [](const Obstacle& obstacle, const RealArray& x) {
        const Eigen::Vector3d xv = as_vector3(x, "x");
        if (!xv.allFinite()) throw py::value_error("x: coordinates are not finite");
        return project(obstacle, xv);
      },
      py::arg("obstacle"), py::arg("x"),
      "Closest-point projection of the point x (3,) onto a RigidPlane, RigidBox, RigidCylinder or\n"
      "RigidSphere");
}

}  // namespace hypercontact::python
