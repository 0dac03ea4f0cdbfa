#pragma once
// The kernels, base pdfs and domains every law and goodness-of-fit test runs over, as
// runtime lists of named values (so one loop covers kernel × base pdf × α).
#include <functional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <iris/sampling/sampling.hpp>
#include <iris/spectrum/named.hpp>

namespace iris::test {

/// \brief A named value.
template <class T>
struct named {
    std::string name;
    T value;
};

/// \brief The kernels under test: the defaults, and the edge cases docs/method.md §5 asks for
/// (a window at the domain edge, a width-0 box, overlapping windows, a tiny σ).
inline auto kernels() {
    using namespace iris::restriction;
    multi_box<3> overlapping;
    overlapping.centres_nm = {500.0f, 505.0f, 700.0f};
    overlapping.widths_nm = {20.0f, 20.0f, 0.0f};
    multi_box<3> at_edges;
    at_edges.centres_nm = {380.0f, 580.0f, 780.0f};
    return std::make_tuple(named<unrestricted>{"unrestricted", {}},                          //
                           named<box>{"box", {}},                                            //
                           named<box>{"box@380", {380.0f, 20.0f}},                           //
                           named<box>{"box-width0", {600.0f, 0.0f}},                         //
                           named<multi_box<3>>{"multibox3", {}},                             //
                           named<multi_box<3>>{"multibox3-overlap", overlapping},            //
                           named<multi_box<3>>{"multibox3-edges", at_edges},                 //
                           named<gaussian>{"gaussian", {}},                                  //
                           named<gaussian>{"gaussian-sigma1e-3", {550.0f, 1e-3f}},           //
                           named<gaussian>{"gaussian@780", {780.0f, 30.0f}});
}

/// \brief A table that is 0 below 500 nm and on 600–650 nm: an emitter with dark bands,
/// so some windows hold no mass at all (the restricted fallback) and cells are massless.
inline spectral_pdf::tabulated dark_bands() {
    return spectral_pdf::tabulated({300, 499, 500, 550, 599, 600, 650, 651, 900}, {0, 0, 1, 3, 2, 0, 0, 1, 1});
}

inline auto base_pdfs() {
    using namespace iris::spectral_pdf;
    return std::make_tuple(named<uniform>{"uniform", {}},  //
                           named<visible>{"visible", {}},  //
                           named<illuminant>{"illuminant-D65", illuminant(find_illuminant("D65")->spectrum())},
                           named<illuminant>{"illuminant-LED-RGB1", illuminant(find_illuminant("LED-RGB1")->spectrum())},
                           named<tabulated>{"dark-bands", dark_bands()});
}

inline std::vector<named<spectral_domain>> domains() { return {{"380-780", {}}, {"400-700", {400.0f, 700.0f}}}; }

/// \brief Call f(kernel, base) for every base pdf.
template <class F, class K>
void for_each_base(F& f, const K& k) {
    std::apply([&](const auto&... b) { (f(k, b), ...); }, base_pdfs());
}

/// \brief Call f(kernel, base) for every pair (kernel and base are `named<…>`).
template <class F>
void for_each_pair(F&& f) {
    std::apply([&](const auto&... k) { (for_each_base(f, k), ...); }, kernels());
}

}  // namespace iris::test
