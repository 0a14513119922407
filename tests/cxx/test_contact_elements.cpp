// Flat storage of element contributions: offsets, accessors, the order of appended elements.
#include <gtest/gtest.h>

#include <hypercontact/contact_elements.hpp>

namespace hypercontact {
namespace {

TEST(ContactElements, AppendedElementsReadBackWithTheirSizes) {
  ContactElements c;
  EXPECT_EQ(c.size(), 0u);
  {
    ContactElements::Slot e = c.append(7, 2, 3);
    EXPECT_EQ(e.residual.size(), 2);
    EXPECT_EQ(e.tangent.rows(), 2);
    EXPECT_EQ(e.tangent.cols(), 3);
    EXPECT_EQ(e.residual.norm() + e.tangent.norm(), 0.0);  // starts at zero
    e.rows[0] = 4, e.rows[1] = -1;
    e.columns[0] = 4, e.columns[1] = -1, e.columns[2] = 9;
    e.residual << 1.5, 2.5;
    e.tangent << 1, 2, 3, 4, 5, 6;
  }
  {
    ContactElements::Slot e = c.append(2, 1, 1);
    e.rows[0] = e.columns[0] = 0;
    e.residual[0] = -1;
    e.tangent(0, 0) = 8;
  }
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c.point, (std::vector<std::int32_t>{7, 2}));
  EXPECT_EQ(c.row_offsets, (std::vector<std::int32_t>{0, 2, 3}));
  EXPECT_EQ(c.column_offsets, (std::vector<std::int32_t>{0, 3, 4}));
  EXPECT_EQ(c.tangent_offsets, (std::vector<std::int64_t>{0, 6, 7}));
  EXPECT_EQ(std::vector<std::int32_t>(c.columns(0).begin(), c.columns(0).end()),
            (std::vector<std::int32_t>{4, -1, 9}));
  EXPECT_EQ(c.rows(1)[0], 0);
  EXPECT_EQ(c.element_residual(0)[1], 2.5);
  EXPECT_EQ(c.element_residual(1)[0], -1.0);
  EXPECT_EQ(c.element_tangent(0)(1, 0), 4.0);  // row-major
  EXPECT_EQ(c.tangent[3], 4.0);
  EXPECT_EQ(c.element_tangent(1)(0, 0), 8.0);
}

}  // namespace
}  // namespace hypercontact
