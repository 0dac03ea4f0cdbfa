// Compile-time checks of the spectrum types: concepts, widths, constexpr-ness,
// including negative cases (what must NOT compile or satisfy a concept).
#include <iris/iris.hpp>

#include <string>
#include <type_traits>

namespace {

template <std::size_t N>
concept valid_width = requires { typename iris::sampled_spectrum<N>; iris::sampled_spectrum<N>::size(); };

// Spectrum concept: models and non-models
static_assert(iris::Spectrum<iris::constant_spectrum>);
static_assert(iris::Spectrum<iris::tabulated_spectrum>);
static_assert(iris::Spectrum<iris::blackbody_spectrum>);
static_assert(!iris::Spectrum<int>);
static_assert(!iris::Spectrum<std::string>);
static_assert(!iris::Spectrum<iris::sampled_spectrum<4>>);

// IOR concept
static_assert(iris::IorModel<iris::cauchy_ior>);
static_assert(iris::IorModel<iris::sellmeier_ior>);
static_assert(!iris::IorModel<iris::constant_spectrum>);
static_assert(!iris::IorModel<double>);

// widths: 1..32 are fine, 0 is rejected by the requires-clause
static_assert(iris::sampled_spectrum<1>::size() == 1);
static_assert(iris::sampled_wavelengths<32>::size() == 32);
static_assert(valid_width<4>);
static_assert(!valid_width<0>);

// value semantics: cheap, trivially copyable, no hidden allocation
static_assert(std::is_trivially_copyable_v<iris::sampled_spectrum<4>>);
static_assert(std::is_trivially_copyable_v<iris::sampled_wavelengths<4>>);
static_assert(sizeof(iris::sampled_spectrum<4>) == 4 * sizeof(float));

// arithmetic is usable in constant expressions
constexpr iris::sampled_spectrum<2> a({1.0f, 2.0f});
static_assert((a + a)[1] == 4.0f);
static_assert((a * 3.0f).sum() == 9.0f);
static_assert(iris::constant_spectrum{2.0}(555.0) == 2.0);
static_assert(iris::cie::y_bar(555.0) == 1.0);
static_assert(iris::glasses[0].name == "N-BK7");
static_assert(iris::illuminants.size() == 11);

// mixing widths is a type error, not a silent broadcast
template <class A, class B>
concept addable = requires(A x, B y) { x + y; };
static_assert(addable<iris::sampled_spectrum<4>, iris::sampled_spectrum<4>>);
static_assert(!addable<iris::sampled_spectrum<4>, iris::sampled_spectrum<8>>);

}  // namespace
