#include "core/system/numbers.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "core/system/error.h"

namespace photon {

bool parseDecimal(const std::string& text, double& value) {
    bool decimal = !text.empty() && text.find_first_not_of("0123456789+-.eE") == std::string::npos;
    char* end = nullptr;
    errno = 0;
    value = decimal ? std::strtod(text.c_str(), &end) : 0.0;
    return decimal && end == text.c_str() + text.size();
}

std::string formatNumber(double x) {
    char text[32];
    for (int digits = 6; digits <= 17; ++digits) {
        std::snprintf(text, sizeof text, "%.*g", digits, x);
        if (std::strtod(text, nullptr) == x) {
            break;
        }
    }
    return text;
}

std::string Range::describe() const {
    if (lo == 0.0 && hi == std::numeric_limits<double>::infinity()) {
        return openLo ? "positive" : "non-negative";
    }
    return std::string("in ") + (openLo ? "(" : "[") + formatNumber(lo) + ", " + formatNumber(hi) + (openHi ? ")" : "]");
}

double parseNumber(const std::string& text, const Range& range, const std::string& where) {
    double value = 0.0;
    if (!parseDecimal(text, value)) {
        throw InputError(where + ": must be a number " + range.describe() + " (got '" + text + "', not a number)");
    }
    if (!std::isfinite(value) || !range.contains(value)) {
        throw InputError(where + ": must be a finite number " + range.describe() + " (got " + text + ")");
    }
    return value;
}

}  // namespace photon
