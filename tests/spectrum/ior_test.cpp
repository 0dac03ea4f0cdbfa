#include <gtest/gtest.h>

#include <iris/spectrum/ior.hpp>
#include <iris/spectrum/named.hpp>

namespace {

TEST(Ior, NBk7MatchesSchottCatalogue) {
    const auto g = iris::find_glass("N-BK7");
    ASSERT_TRUE(g.has_value());
    EXPECT_NEAR(g->sellmeier.n(iris::fraunhofer_d), 1.51680, 5e-6);
    EXPECT_NEAR(iris::abbe_number(g->sellmeier), 64.17, 5e-3);
}

TEST(Ior, EveryGlassIsNormalAndDispersive) {
    EXPECT_EQ(iris::glasses.size(), 14u);
    for (const auto& g : iris::glasses) {
        double prev = 1e9;
        for (double l = 380.0; l <= 780.0; l += 10.0) {
            const double n = g.sellmeier.n(l);
            EXPECT_GT(n, 1.4) << g.name;
            EXPECT_LT(n, 2.0) << g.name;
            EXPECT_LT(n, prev) << g.name << " at " << l << " nm: normal dispersion means n falls with λ";
            prev = n;
            // the Cauchy fit stays within its documented worst residual (6.2e-3, N-SF11)
            EXPECT_NEAR(g.cauchy.n(l), n, 6.2e-3) << g.name << " at " << l;
        }
    }
}

TEST(Ior, CauchyFormula) {
    constexpr iris::cauchy_ior c{1.5, 0.01};
    static_assert(c.n(1000.0) == 1.51);
    EXPECT_DOUBLE_EQ(c.n(500.0), 1.5 + 0.01 / 0.25);
}

TEST(Ior, UnknownGlassIsNotFound) {
    EXPECT_FALSE(iris::find_glass("BK7").has_value());
    EXPECT_FALSE(iris::find_glass("").has_value());
}

}  // namespace
