// The median of a sample: what photon-render, photon-bench and photon-view report of frame and
// stage times (robust to the first frames' pipeline builds and to the odd slow frame).
#pragma once

#include <algorithm>
#include <vector>

namespace photon {

// The middle value, or the mean of the middle two for an even count; 0 for an empty sample.
inline double median(std::vector<double> v) {
    if (v.empty()) {
        return 0.0;
    }
    std::sort(v.begin(), v.end());
    std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace photon
