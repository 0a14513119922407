// The evaluations allocate per evaluation, not per slave point: with four times the points (all
// of them closed), the number of heap allocations grows by far less than the number of points
// (only the flat arrays of the state and the elements grow, geometrically). Every allocation of
// this executable (operator new and Eigen's) goes through the malloc defined here, which counts.
#include <gtest/gtest.h>

#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <functional>
#include <hypercontact/rigid_contact_friction.hpp>
#include <hypercontact/surface_contact_friction.hpp>
#include <vector>

#include "surface_scene.hpp"

namespace {
std::atomic<long> allocations{0};
}  // namespace

extern "C" void* __libc_malloc(std::size_t size);
extern "C" void* malloc(std::size_t size) {
  allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(size);
}

namespace hypercontact {
namespace {

/// Allocations made by f().
long count_allocations(const std::function<void()>& f) {
  const long before = allocations.load();
  f();
  return allocations.load() - before;
}

/// n × n slave nodes below a flat master of 4 × 4 quadrilaterals (or 32 triangles), each with
/// every facet a candidate; Gauss points of (n/2)² slave quadrilaterals with `gauss`.
test::SurfaceScene surface(int n, bool gauss, bool triangles) {
  test::SurfaceScene s;
  s.add_master_grid(
      4, 4, 0.0, 0.0, 1.0, [](double x, double y) { return 0.02 * x * y; }, triangles);
  const double h = 3.6 / n;
  for (int j = 0; j < n; j += gauss ? 2 : 1)
    for (int i = 0; i < n; i += gauss ? 2 : 1) {
      const double x = 0.2 + h * i, y = 0.2 + h * j;
      if (gauss)
        s.add_slave_quad(
            {{x, y, -0.05}, {x + h, y, -0.05}, {x + h, y + h, -0.05}, {x, y + h, -0.05}}, 0.01);
      else
        s.add_slave_node({x, y, -0.05}, 0.01);
    }
  return s;
}

/// The allocations for N = n² points (n = 16) and for 4 N points differ by less than N/2.
void expect_no_allocation_per_point(const std::function<long(int)>& allocations_for_points) {
  const int n = 16;
  const long small = allocations_for_points(n), large = allocations_for_points(2 * n);
  EXPECT_LT(large - small, n * n / 2) << small << " allocations for n, " << large << " for 2n";
}

TEST(EvaluationAllocations, SurfaceContactAndFrictionDoNotAllocatePerPoint) {
  for (const bool gauss : {false, true})
    for (const bool triangles : {false, true}) {
      const auto normal = [&](int n) {
        const test::SurfaceScene s = surface(n, gauss, triangles);
        return count_allocations([&] {
          const SurfaceContactEvaluation e = evaluate_surface_contact(s.input());
          EXPECT_EQ(e.elements.size(), s.point_area.size());  // all closed
        });
      };
      const auto friction = [&](int n) {
        const test::SurfaceScene s = surface(n, gauss, triangles);
        const std::size_t np = s.point_area.size();
        const std::vector<std::int32_t> old_facet(np, 0);
        const std::vector<double> xi_old(2 * np, 0.0), t_old(3 * np, 1.0);
        return count_allocations([&] {
          evaluate_surface_friction({s.input(), old_facet, xi_old, t_old, 100.0, 0.3});
        });
      };
      expect_no_allocation_per_point(normal);
      expect_no_allocation_per_point(friction);
    }
}

TEST(EvaluationAllocations, RigidContactAndFrictionDoNotAllocatePerNode) {
  const auto rigid = [](int n) {
    std::vector<double> x, area(n * n, 0.1), xi_old, t_old(3 * n * n, 1.0);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        x.insert(x.end(), {0.1 * i, 0.1 * j, 0.2});
        xi_old.insert(xi_old.end(), {0.1 * i + 0.01, 0.1 * j, 0.2});
      }
    const std::vector<std::int32_t> dofs = test::identity_dofs(x.size());
    // Inside a cylinder of radius 50 along x (curved: every node closed, ∂n/∂x ≠ 0).
    const RigidContactInput contact{RigidCylinder{{0, 0, 50}, {1, 0, 0}, 50.0}, x, area, dofs, 1e3};
    return count_allocations([&] {
      EXPECT_EQ(evaluate_rigid_contact(contact).num_closed, n * n);
      evaluate_rigid_friction({contact, xi_old, t_old, 100.0, 0.3});
    });
  };
  expect_no_allocation_per_point(rigid);
}

}  // namespace
}  // namespace hypercontact
