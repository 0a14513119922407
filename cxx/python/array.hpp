// Conversions between numpy arrays and the kernels' spans and Eigen types, with shape checks.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Core>
#include <algorithm>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace hypercontact::python {

namespace py = pybind11;

/// Read-only float64 input; lists and other dtypes are converted.
using RealArray = py::array_t<double, py::array::c_style | py::array::forcecast>;
/// Read-only int32 input; lists are converted, int64 arrays are refused (no silent truncation).
using IndexArray = py::array_t<std::int32_t, py::array::c_style>;

/// Dimension that matches any extent in check_shape.
constexpr py::ssize_t any = -1;

inline std::string shape_string(const std::vector<py::ssize_t>& shape) {
  std::string s = "(";
  for (std::size_t i = 0; i < shape.size(); ++i)
    s += (i ? ", " : "") + (shape[i] == any ? std::string("*") : std::to_string(shape[i]));
  return s + (shape.size() == 1 ? ",)" : ")");
}

/// Raises ValueError "name: expected shape (*, 3), got (4,)" unless `a` has shape `expected`.
inline void check_shape(const py::array& a, const char* name,
                        const std::vector<py::ssize_t>& expected) {
  const std::vector<py::ssize_t> actual(a.shape(), a.shape() + a.ndim());
  bool ok = actual.size() == expected.size();
  for (std::size_t i = 0; ok && i < actual.size(); ++i)
    ok = expected[i] == any || expected[i] == actual[i];
  if (!ok)
    throw py::value_error(std::string(name) + ": expected shape " + shape_string(expected) +
                          ", got " + shape_string(actual));
}

template <typename T, int Flags>
std::span<const T> as_span(const py::array_t<T, Flags>& a) {
  return {a.data(), static_cast<std::size_t>(a.size())};
}

inline Eigen::Vector3d as_vector3(const RealArray& a, const char* name) {
  check_shape(a, name, {3});
  return Eigen::Vector3d(a.data());
}

/// The writable float64 C-contiguous 1-D array `a` as a span (no copy); raises otherwise.
inline std::span<double> as_writable_span(py::array& a, const char* name) {
  if (!a.dtype().is(py::dtype::of<double>()))
    throw py::type_error(std::string(name) + ": expected a float64 array");
  check_shape(a, name, {any});
  if (!(a.flags() & py::array::c_style))
    throw py::value_error(std::string(name) + ": expected a contiguous array");
  if (!a.writeable()) throw py::value_error(std::string(name) + ": array is not writable");
  return {static_cast<double*>(a.mutable_data()), static_cast<std::size_t>(a.size())};
}

inline py::array_t<double> to_numpy(const std::vector<double>& v) {
  return py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());
}

/// A flat vector as a numpy array of `width` columns (1: a 1-D array).
template <typename T>
py::array_t<T> to_numpy_table(const std::vector<T>& v, py::ssize_t width) {
  py::array_t<T> a(width == 1 ? std::vector<py::ssize_t>{static_cast<py::ssize_t>(v.size())}
                              : std::vector<py::ssize_t>{static_cast<py::ssize_t>(v.size()) / width, width});
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

}  // namespace hypercontact::python
