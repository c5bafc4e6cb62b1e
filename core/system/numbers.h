// Numbers as the programs read and show them: a range a value must lie in (and how a message
// says it), decimal text parsed strictly, and the shortest text that reads back as the same
// double. Settings, loaders and options share them; they know nothing of what the numbers mean.
#pragma once

#include <string>

namespace photon {

// The values a number may take, for checks and their messages.
struct Range {
    double lo, hi;
    bool openLo = false, openHi = false;

    bool contains(double x) const { return (openLo ? x > lo : x >= lo) && (openHi ? x < hi : x <= hi); }
    std::string describe() const;  // "positive", "in [0, 1)", ...
};

// A number as a message shows it: shortest round-trip form ("1e+39", "0.04").
std::string formatNumber(double x);

// Decimal numbers only: no "nan", "inf" or hexadecimal, nothing after the number (1e999 is
// infinite, for the range checks to refuse). False if `text` is not one.
bool parseDecimal(const std::string& text, double& value);

// A number of the command line that is no render setting (photon-render's --time), parsed and
// checked as the settings are: a finite decimal number within `range`, else InputError
// "<where>: must be ...".
double parseNumber(const std::string& text, const Range& range, const std::string& where);

}  // namespace photon
