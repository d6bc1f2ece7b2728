#include <gtest/gtest.h>
#include "grid/Grid.hpp"
TEST(Grid, SpacingAndOwnership) {
  gf::Grid g(PETSC_COMM_WORLD, 32, 16, 0.8, 0.2);
  EXPECT_DOUBLE_EQ(g.hx(), 0.025);
  EXPECT_DOUBLE_EQ(g.hy(), 0.0125);
  long long owned = g.box().xm * g.box().ym;
  EXPECT_EQ(g.sum(owned), 32 * 16);
}
