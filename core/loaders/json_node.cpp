#include "core/loaders/json_node.h"

#include <algorithm>

#include "core/system/error.h"

namespace photon {
namespace {

using nlohmann::json;

// ---- JSON syntax --------------------------------------------------------------------------------

// A SAX consumer that only records the first syntax error: where it is and what nlohmann says.
struct SyntaxErrorLocator : nlohmann::json_sax<json> {
    std::size_t byte = 0;  // 1-based index of the last character read; size + 1 at the end of input
    std::string message;

    bool null() override { return true; }
    bool boolean(bool) override { return true; }
    bool number_integer(number_integer_t) override { return true; }
    bool number_unsigned(number_unsigned_t) override { return true; }
    bool number_float(number_float_t, const string_t&) override { return true; }
    bool string(string_t&) override { return true; }
    bool binary(binary_t&) override { return true; }
    bool start_object(std::size_t) override { return true; }
    bool key(string_t&) override { return true; }
    bool end_object() override { return true; }
    bool start_array(std::size_t) override { return true; }
    bool end_array() override { return true; }
    bool parse_error(std::size_t position, const std::string&, const nlohmann::detail::exception& e) override {
        byte = position;
        message = e.what();
        return false;
    }
};

// nlohmann's message without its decorations: "[json.exception.parse_error.101] parse error at line
// 1, column 8: syntax error while parsing value - invalid literal; last read: 'N'" → "invalid
// literal; last read: 'N'".
std::string essentialPart(std::string message) {
    auto dropThrough = [&](const std::string& prefix, const std::string& separator) {
        if (message.compare(0, prefix.size(), prefix) == 0) {
            std::size_t end = message.find(separator);
            if (end != std::string::npos) {
                message.erase(0, end + separator.size());
            }
        }
    };
    dropThrough("[json.exception.", "] ");
    dropThrough("parse error", ": ");
    dropThrough("syntax error while parsing ", " - ");
    // The text it quotes ("number overflow parsing '1e999'") may be a whole 100 KB number.
    std::size_t open = message.find('\'');
    std::size_t close = message.rfind('\'');
    if (open != std::string::npos && close > open) {
        message = message.substr(0, open) + quote(message.substr(open + 1, close - open - 1)) + message.substr(close + 1);
    }
    return message;
}

}  // namespace

std::string pointerToken(const std::string& key) {
    std::string out;
    for (char c : key) {
        out += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
    }
    return out;
}

json parseJson(const std::string& text, const std::string& source) {
    std::size_t nul = text.find('\0');
    if (nul != std::string::npos) {
        throw InputError(source + ": byte " + std::to_string(nul + 1) + ": a NUL character, which JSON text never holds");
    }
    json document = json::parse(text, nullptr, /*allow_exceptions=*/false);
    if (!document.is_discarded()) {
        return document;
    }
    // Parse again to find out where and why: the exception-free parse above only says that it failed.
    SyntaxErrorLocator locator;
    json::sax_parse(text, &locator);
    // The offending character (0-based) and its line and column (1-based).
    std::size_t offset = std::min(locator.byte > 0 ? locator.byte - 1 : 0, text.size());
    std::size_t line = 1;
    std::size_t column = 1;
    for (std::size_t i = 0; i < offset; ++i) {
        column = text[i] == '\n' ? 1 : column + 1;
        line += text[i] == '\n' ? 1 : 0;
    }
    throw InputError(printable(source + ": line " + std::to_string(line) + ", column " +
                               std::to_string(column) + ": " + essentialPart(locator.message)));
}

}  // namespace photon
