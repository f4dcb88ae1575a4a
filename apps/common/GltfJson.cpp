// JSON for the importer's own checks. Strict where the grammar is (so the tree is what any parser would
// build), lenient on UTF-8 inside strings (tinygltf's parser judges that, and reports it).
#include "apps/common/GltfJson.h"

#include <algorithm>
#include <cctype>
#include <charconv>

namespace ripple::apps::gltf {

uint32_t jsonNestingDepth(std::string_view json) {
    uint32_t depth = 0, deepest = 0;
    bool inString = false;
    for (size_t i = 0; i < json.size(); ++i) {
        const char c = json[i];
        if (inString) {
            if (c == '\\') ++i;  // the escaped character cannot end the string
            else if (c == '"') inString = false;
        } else if (c == '"') {
            inString = true;
        } else if (c == '[' || c == '{') {
            deepest = std::max(deepest, ++depth);
        } else if ((c == ']' || c == '}') && depth > 0) {
            --depth;
        }
    }
    return deepest;
}

const JsonValue* JsonValue::find(std::string_view key) const {
    for (auto it = members.rbegin(); it != members.rend(); ++it)
        if (it->first == key) return &it->second;
    return nullptr;
}

bool JsonValue::isIntegerToken() const {
    return kind == Kind::Number && token.find_first_of(".eE") == std::string_view::npos;
}

double JsonValue::number() const {
    double v = 0.0;
    std::from_chars(token.data(), token.data() + token.size(), v);  // the parser checked the grammar
    return v;
}

const char* JsonValue::kindName() const {
    switch (kind) {
        case Kind::Null: return "null";
        case Kind::Bool: return "a boolean";
        case Kind::Number: return "a number";
        case Kind::String: return "a string";
        case Kind::Array: return "an array";
        case Kind::Object: return "an object";
    }
    return "a value";
}

namespace {

void appendUtf8(std::string& out, uint32_t code) {
    if (code < 0x80) {
        out += char(code);
    } else if (code < 0x800) {
        out += char(0xC0 | (code >> 6));
        out += char(0x80 | (code & 0x3F));
    } else if (code < 0x10000) {
        out += char(0xE0 | (code >> 12));
        out += char(0x80 | ((code >> 6) & 0x3F));
        out += char(0x80 | (code & 0x3F));
    } else {
        out += char(0xF0 | (code >> 18));
        out += char(0x80 | ((code >> 12) & 0x3F));
        out += char(0x80 | ((code >> 6) & 0x3F));
        out += char(0x80 | (code & 0x3F));
    }
}

uint32_t hex4(std::string_view s, size_t at) {
    uint32_t v = 0;
    std::from_chars(s.data() + at, s.data() + at + 4, v, 16);  // the parser checked the four digits
    return v;
}

}  // namespace

std::string JsonValue::text() const {
    std::string out;
    out.reserve(token.size());
    for (size_t i = 0; i < token.size(); ++i) {
        if (token[i] != '\\') {
            out += token[i];
            continue;
        }
        const char e = token[++i];
        switch (e) {
            case 'b': out += '\b'; break;
            case 'f': out += '\f'; break;
            case 'n': out += '\n'; break;
            case 'r': out += '\r'; break;
            case 't': out += '\t'; break;
            case 'u': {
                uint32_t code = hex4(token, i + 1);
                i += 4;
                // A high surrogate followed by an escaped low one is one code point; a lone one stays U+FFFD.
                if (code >= 0xD800 && code < 0xDC00 && i + 6 < token.size() && token[i + 1] == '\\' &&
                    token[i + 2] == 'u') {
                    const uint32_t low = hex4(token, i + 3);
                    if (low >= 0xDC00 && low < 0xE000) {
                        code = 0x10000 + ((code - 0xD800) << 10) + (low - 0xDC00);
                        i += 6;
                    }
                }
                if (code >= 0xD800 && code < 0xE000) code = 0xFFFD;
                appendUtf8(out, code);
                break;
            }
            default: out += e;  // '"', '\\', '/'
        }
    }
    return out;
}

namespace {

class Parser {
public:
    explicit Parser(std::string_view text) : s_(text) {}

    std::optional<JsonValue> document(std::string& error) {
        if (s_.substr(0, 3) == "\xEF\xBB\xBF") at_ = 3;
        JsonValue root;
        bool ok = value(root);
        skipSpace();
        if (ok && at_ < s_.size() && s_[at_] != '\0') ok = fail("text after the JSON value");
        if (!ok) {
            error = error_;
            return std::nullopt;
        }
        return root;
    }

private:
    bool fail(const char* what) {
        if (error_.empty()) {
            size_t line = 1, column = 1;
            for (size_t i = 0; i < at_ && i < s_.size(); ++i) {
                if (s_[i] == '\n') ++line, column = 1;
                else ++column;
            }
            error_ = "line " + std::to_string(line) + ", column " + std::to_string(column) + ": " + what;
        }
        return false;
    }

    void skipSpace() {
        while (at_ < s_.size() && (s_[at_] == ' ' || s_[at_] == '\t' || s_[at_] == '\n' || s_[at_] == '\r')) ++at_;
    }

    bool literal(std::string_view word) {
        if (s_.substr(at_, word.size()) != word) return fail("invalid literal");
        at_ += word.size();
        return true;
    }

    bool value(JsonValue& out) {
        skipSpace();
        if (at_ >= s_.size()) return fail("unexpected end of input");
        switch (s_[at_]) {
            case '{': return object(out);
            case '[': return array(out);
            case '"': out.kind = JsonValue::Kind::String; return string(out.token);
            case 't': out.kind = JsonValue::Kind::Bool; out.boolean = true; return literal("true");
            case 'f': out.kind = JsonValue::Kind::Bool; return literal("false");
            case 'n': out.kind = JsonValue::Kind::Null; return literal("null");
            default: out.kind = JsonValue::Kind::Number; return number(out.token);
        }
    }

    bool digits() {
        const size_t start = at_;
        while (at_ < s_.size() && s_[at_] >= '0' && s_[at_] <= '9') ++at_;
        return at_ > start;
    }

    bool number(std::string_view& token) {
        const size_t start = at_;
        if (at_ < s_.size() && s_[at_] == '-') ++at_;
        if (at_ < s_.size() && s_[at_] == '0') ++at_;
        else if (!digits()) return fail("invalid value");
        if (at_ < s_.size() && s_[at_] == '.' && (++at_, !digits())) return fail("invalid number: no digit after '.'");
        if (at_ < s_.size() && (s_[at_] == 'e' || s_[at_] == 'E')) {
            ++at_;
            if (at_ < s_.size() && (s_[at_] == '+' || s_[at_] == '-')) ++at_;
            if (!digits()) return fail("invalid number: no digit in the exponent");
        }
        token = s_.substr(start, at_ - start);
        return true;
    }

    bool string(std::string_view& raw) {
        const size_t start = ++at_;
        while (at_ < s_.size() && s_[at_] != '"') {
            const unsigned char c = static_cast<unsigned char>(s_[at_]);
            if (c < 0x20) return fail("control character in a string");
            if (c == '\\') {
                if (++at_ >= s_.size()) break;
                const char e = s_[at_];
                if (e == 'u') {
                    for (int k = 1; k <= 4; ++k)
                        if (at_ + size_t(k) >= s_.size() || !std::isxdigit(static_cast<unsigned char>(s_[at_ + size_t(k)])))
                            return fail("invalid \\u escape");
                    at_ += 4;
                } else if (std::string_view("\"\\/bfnrt").find(e) == std::string_view::npos) {
                    return fail("invalid escape in a string");
                }
            }
            ++at_;
        }
        if (at_ >= s_.size()) return fail("unterminated string");
        raw = s_.substr(start, at_ - start);
        ++at_;
        return true;
    }

    bool array(JsonValue& out) {
        out.kind = JsonValue::Kind::Array;
        ++at_;
        skipSpace();
        if (at_ < s_.size() && s_[at_] == ']') return ++at_, true;
        while (true) {
            if (!value(out.items.emplace_back())) return false;
            skipSpace();
            if (at_ >= s_.size()) return fail("unterminated array");
            if (s_[at_] == ']') return ++at_, true;
            if (s_[at_] != ',') return fail("expected ',' or ']'");
            ++at_;
        }
    }

    bool object(JsonValue& out) {
        out.kind = JsonValue::Kind::Object;
        ++at_;
        skipSpace();
        if (at_ < s_.size() && s_[at_] == '}') return ++at_, true;
        while (true) {
            skipSpace();
            if (at_ >= s_.size() || s_[at_] != '"') return fail("expected a member name");
            JsonValue key;
            key.kind = JsonValue::Kind::String;
            if (!string(key.token)) return false;
            skipSpace();
            if (at_ >= s_.size() || s_[at_] != ':') return fail("expected ':'");
            ++at_;
            auto& member = out.members.emplace_back(key.text(), JsonValue{});
            if (!value(member.second)) return false;
            skipSpace();
            if (at_ >= s_.size()) return fail("unterminated object");
            if (s_[at_] == '}') return ++at_, true;
            if (s_[at_] != ',') return fail("expected ',' or '}'");
            ++at_;
        }
    }

    std::string_view s_;
    size_t at_ = 0;
    std::string error_;
};

}  // namespace

std::optional<JsonValue> parseJson(std::string_view json, std::string& error) {
    return Parser(json).document(error);
}

}  // namespace ripple::apps::gltf
