// A JSON value together with its JSON pointer, so that every check can say exactly where it
// failed: "<source>: <pointer>: <reason>", one line. The scene loader reads scene files through it.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "core/settings/setting_specs.h"
#include "core/system/error.h"

namespace photon {

// Parses JSON text; throws InputError("<source>: line L, column C: <reason>") if it is not JSON.
// NUL bytes anywhere (JSON text never holds one raw) are refused too.
nlohmann::json parseJson(const std::string& text, const std::string& source);

// One reference token of a JSON pointer (RFC 6901): '~' → "~0", '/' → "~1".
std::string pointerToken(const std::string& key);

inline constexpr Range kFinite{-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(), true, true};
inline constexpr Range kPositive{0.0, std::numeric_limits<double>::infinity(), true, true};
inline constexpr Range kNonNegative{0.0, std::numeric_limits<double>::infinity(), false, true};
inline constexpr Range kUnit{0.0, 1.0, false, false};

// A JSON value and where it is. Every accessor checks the type first, so nlohmann never throws here.
class JsonNode {
public:
    JsonNode(const nlohmann::json& value, std::string pointer, const std::string& source)
        : value_(value), pointer_(std::move(pointer)), source_(source) {}

    // "<source>: <pointer>", the place for messages.
    std::string where() const { return source_ + ": " + (pointer_.empty() ? "/" : pointer_); }

    [[noreturn]] void fail(const std::string& reason) const { throw InputError(printable(where() + ": " + reason)); }

    const nlohmann::json& value() const { return value_; }

    // ---- Objects -------------------------------------------------------------------------------

    // Requires an object whose keys are all among `allowed`.
    void allowKeys(std::initializer_list<const char*> allowed) const {
        expectObject();
        for (const auto& member : value_.items()) {
            if (std::none_of(allowed.begin(), allowed.end(), [&](const char* k) { return member.key() == k; })) {
                child(member.key()).fail("unknown key");
            }
        }
    }

    bool has(const char* key) const { return value_.is_object() && value_.contains(key); }

    // A required key.
    JsonNode operator[](const char* key) const {
        expectObject();
        if (!value_.contains(key)) {
            fail(std::string("missing required key '") + key + "'");
        }
        return child(key);
    }

    std::vector<std::pair<std::string, JsonNode>> members() const {
        expectObject();
        std::vector<std::pair<std::string, JsonNode>> out;
        for (const auto& member : value_.items()) {
            out.emplace_back(member.key(), child(member.key()));
        }
        return out;
    }

    // ---- Arrays --------------------------------------------------------------------------------

    std::vector<JsonNode> elements() const {
        if (!value_.is_array()) {
            fail(expected("an array"));
        }
        std::vector<JsonNode> out;
        for (std::size_t i = 0; i < value_.size(); ++i) {
            out.push_back(element(i));
        }
        return out;
    }

    // ---- Values --------------------------------------------------------------------------------

    bool isNumber() const { return value_.is_number(); }

    // A number, as the float the renderer will see, checked against `range`.
    float number(const Range& range = kFinite) const {
        if (!value_.is_number()) {
            fail(expected("a number"));
        }
        double x = value_.get<double>();
        if (!(std::abs(x) <= std::numeric_limits<float>::max())) {
            fail("must be a finite number within the range of a float (got " + value_.dump() + ")");
        }
        if (!range.contains(x)) {
            fail("must be " + range.describe() + " (got " + value_.dump() + ")");
        }
        // The float nearest x, stepped back inside where rounding left the range (0.99 as a float
        // is 0.9900000095; 1e-50 in a positive range rounds to 0).
        auto f = static_cast<float>(x);
        for (int step = 0; step < 2 && !range.contains(f); ++step) {
            f = std::nextafter(f, f > x ? -std::numeric_limits<float>::infinity() : std::numeric_limits<float>::infinity());
        }
        return f;
    }

    // An integral number in [lo, hi]; 16 and 16.0 are both integral.
    std::uint32_t integer(std::uint32_t lo, std::uint32_t hi) const {
        if (!value_.is_number()) {
            fail(expected("an integer"));
        }
        double x = value_.get<double>();
        if (!(x >= lo && x <= hi && x == std::floor(x))) {
            fail("must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "] (got " +
                 value_.dump() + ")");
        }
        return static_cast<std::uint32_t>(x);
    }

    bool boolean() const {
        if (!value_.is_boolean()) {
            fail(expected("true or false"));
        }
        return value_.get<bool>();
    }

    const std::string& string() const {
        if (!value_.is_string()) {
            fail(expected("a string"));
        }
        return value_.get_ref<const std::string&>();
    }

    // One of the names of a settings enum (settings.h).
    template <typename E>
    E setting() const {
        E out{};
        if (!parse(string(), out)) {
            fail("unknown value '" + string() + "' (expected " + choices(out) + ")");
        }
        return out;
    }

    glm::vec3 vec3() const { return triple("expected an array of 3 numbers", kFinite); }

    glm::vec3 rgb(const Range& range) const { return triple("expected an RGB array of 3 numbers", range); }

    // An array of 3 numbers, each checked against `range`; `mismatch` is the message for anything else.
    glm::vec3 triple(const char* mismatch, const Range& range) const {
        if (!value_.is_array() || value_.size() != 3) {
            fail(mismatch);
        }
        return {element(0).number(range), element(1).number(range), element(2).number(range)};
    }

    // A vector the renderer normalises.
    glm::vec3 direction() const {
        glm::vec3 v = vec3();
        checkNormalizable(v, "must be non-zero");
        return v;
    }

    // Fails unless |v|² is a positive, finite float: `ifZero` says why a zero vector is wrong here.
    void checkNormalizable(glm::vec3 v, const std::string& ifZero) const {
        float length2 = glm::dot(v, v);
        if (length2 == 0.0f) {
            fail(ifZero);
        }
        if (!std::isfinite(length2)) {
            fail("too large: the squared length overflows a float");
        }
    }

    // Fails unless the parallelogram spanned by u and v has an area above 1e-12 whose square (which
    // intersection divides by) is a finite float; `ifDegenerate` is the message for a flat one.
    void checkSpan(glm::vec3 u, glm::vec3 v, const std::string& ifDegenerate) const {
        glm::vec3 n = glm::cross(u, v);
        float area2 = glm::dot(n, n);
        if (!std::isfinite(area2)) {
            fail("too large: the area overflows a float");
        }
        if (!(std::sqrt(area2) > 1e-12f)) {
            fail(ifDegenerate);
        }
    }

private:
    void expectObject() const {
        if (!value_.is_object()) {
            fail(expected("an object"));
        }
    }

    std::string expected(const char* what) const {
        return std::string("expected ") + what + " (got " + value_.type_name() + ")";
    }

    JsonNode child(const std::string& key) const {
        return JsonNode(value_.find(key).value(), pointer_ + "/" + pointerToken(key), source_);
    }

    JsonNode element(std::size_t i) const { return JsonNode(value_[i], pointer_ + "/" + std::to_string(i), source_); }

    const nlohmann::json& value_;
    std::string pointer_;
    const std::string& source_;
};

}  // namespace photon
