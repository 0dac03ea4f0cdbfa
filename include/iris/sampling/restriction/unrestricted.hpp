#pragma once
/// \file
/// \brief `restriction::unrestricted`: r_α ≡ 1 for every α — plain HWSS.

#include <string_view>

#include "iris/sampling/restriction/concept.hpp"

namespace iris::restriction {

/// \brief No restriction at all; the baseline every other kernel relaxes towards.
struct unrestricted {
    static constexpr std::string_view name = "unrestricted";
    static constexpr std::size_t max_intervals = 1;

    struct bound {
        static constexpr bool indicator = true;
        interval_set<1> domain;
        constexpr float operator()(float /*lambda_nm*/) const noexcept { return 1.0f; }
        constexpr double average(float /*lo*/, float /*hi*/) const noexcept { return 1.0; }
        constexpr const interval_set<1>& support() const noexcept { return domain; }
    };

    constexpr bound bind(float /*alpha*/, const spectral_domain& d) const noexcept {
        interval_set<1> s;
        s.insert(d.min_nm, d.max_nm);
        return {s.clipped(d)};
    }
};

static_assert(RestrictionKernel<unrestricted>);

}  // namespace iris::restriction
