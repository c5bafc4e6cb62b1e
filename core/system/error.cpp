#include "core/system/error.h"

#include <cstdio>

namespace photon {
namespace {

void escape(std::string& out, unsigned char byte) {
    char text[8];
    std::snprintf(text, sizeof text, "\\x%02x", byte);
    out += text;
}

// Bytes in a valid UTF-8 sequence starting at s[i] (shortest form, no surrogates, at most
// U+10FFFF), or 0.
std::size_t utf8Length(const std::string& s, std::size_t i) {
    auto at = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
    unsigned char c = at(i);
    std::size_t n = c >= 0xf0 && c <= 0xf4 ? 4 : c >= 0xe0 ? 3 : c >= 0xc2 && c < 0xe0 ? 2 : 0;
    if (n == 0 || i + n > s.size()) {
        return 0;
    }
    for (std::size_t k = 1; k < n; ++k) {
        if ((at(i + k) & 0xc0) != 0x80) {
            return 0;
        }
    }
    unsigned char c1 = at(i + 1);
    if ((c == 0xe0 && c1 < 0xa0) || (c == 0xed && c1 >= 0xa0) || (c == 0xf0 && c1 < 0x90) || (c == 0xf4 && c1 >= 0x90)) {
        return 0;
    }
    return n;
}

// The largest cut at most `at` that does not split a UTF-8 sequence of `s`.
std::size_t characterBoundary(const std::string& s, std::size_t at) {
    while (at > 0 && at < s.size() && (static_cast<unsigned char>(s[at]) & 0xc0) == 0x80) {
        at -= 1;
    }
    return at;
}

// The start and the end of a line longer than kMessageMax, the middle said in bytes.
std::string bounded(const std::string& line) {
    if (line.size() <= kMessageMax) {
        return line;
    }
    constexpr std::size_t kHead = 600;
    constexpr std::size_t kTail = 300;
    std::size_t head = characterBoundary(line, kHead);
    std::size_t tail = characterBoundary(line, line.size() - kTail);
    return line.substr(0, head) + " ... [" + std::to_string(tail - head) + " bytes cut] ... " + line.substr(tail);
}

}  // namespace

std::string printable(const std::string& text) {
    std::string out;
    for (std::size_t i = 0; i < text.size();) {
        auto c = static_cast<unsigned char>(text[i]);
        if (c < 0x80) {
            if (c < 0x20 || c == 0x7f) {
                escape(out, c);
            } else {
                out += char(c);
            }
            i += 1;
            continue;
        }
        std::size_t n = utf8Length(text, i);
        bool c1Control = n == 2 && c == 0xc2 && static_cast<unsigned char>(text[i + 1]) < 0xa0;  // U+0080..U+009F
        if (n == 0 || c1Control) {
            for (std::size_t k = 0; k < (n == 0 ? 1 : n); ++k) {
                escape(out, static_cast<unsigned char>(text[i + k]));
            }
            i += n == 0 ? 1 : n;
            continue;
        }
        out.append(text, i, n);
        i += n;
    }
    return bounded(out);
}

std::string quote(const std::string& token) {
    if (token.size() <= kQuotedTokenMax) {
        return "'" + token + "'";
    }
    std::size_t cut = characterBoundary(token, kQuotedTokenMax);
    return "'" + token.substr(0, cut) + "...'";
}

}  // namespace photon
