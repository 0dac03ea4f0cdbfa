// U2 and U3 (first half) at the sizes that detect a 2 % bias of the image's Y with 90 %
// power (agreement.hpp), too long for the default suite, above all under ASan (label `long`, 45 s in release on 2 cores):
//   ctest --preset long -R StatisticalLong
// The default suite runs the same comparisons smaller (statistical_test.cpp) and asserts
// the power it has there.
#include <gtest/gtest.h>

#include "agreement.hpp"

using iris_test::expect_agreement;
using iris_test::falling_cubes_variant;
using iris_test::glass;

TEST(StatisticalLong, U2PaperAgreesWithHwssAfterNtholdOnCornellTo2Percent) {
    expect_agreement(iris::scene::builtin_scene("cornell"), "paper", 128, 96, 8 + 256, 8, 8, "cornell");
}
TEST(StatisticalLong, U2PaperAgreesWithHwssAfterNtholdOnFallingCubesTo2Percent) {
    expect_agreement(iris::scene::builtin_scene("falling-cubes"), "paper", 256, 192, 8 + 640, 8, 8, "falling-cubes");
}
TEST(StatisticalLong, U3PaperIsUnbiasedBeforeNtholdWithoutSpecularDispersionTo2Percent) {
    expect_agreement(falling_cubes_variant(glass::rough), "paper", 128, 96, 240, 640, 0, "rough dispersive glass");
    expect_agreement(falling_cubes_variant(glass::non_dispersive), "paper", 256, 192, 240, 640, 0, "non-dispersive glass");
}
