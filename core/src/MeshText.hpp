// Private helpers of the text mesh readers (PLY ascii, OFF): a cursor over
// whitespace-separated tokens that knows its line, and strict number parsing.
#pragma once

#include <charconv>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

namespace mag::meshText {

// A token for a message: at most 40 characters, unprintable bytes as '?', quoted.
inline std::string quoted(std::string_view text) {
    std::string s(text.substr(0, 40));
    for (char& c : s)
        if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';
    return "'" + s + (text.size() > 40 ? "...'" : "'");
}

inline bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }

// A whole token as a number ("+1", "1e-3"; "nan"/"inf" parse, callers reject them).
inline bool parseNumber(std::string_view token, double& out) {
    if (!token.empty() && token.front() == '+') token.remove_prefix(1);
    if (token.empty()) return false;
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), out);
    return ec == std::errc() && end == token.data() + token.size();
}

// A whole token as an integer in [lowest, highest].
inline bool parseInteger(std::string_view token, std::int64_t lowest, std::int64_t highest, std::int64_t& out) {
    if (!token.empty() && token.front() == '+') token.remove_prefix(1);
    if (token.empty()) return false;
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), out);
    return ec == std::errc() && end == token.data() + token.size() && out >= lowest && out <= highest;
}

// Tokens of a text, in order, with the line (from 1) of the last one returned.
// `comment` (e.g. '#') starts a comment to the end of the line; 0 for none.
class TokenCursor {
public:
    TokenCursor(std::string_view text, std::size_t position, int line, char comment = 0)
        : text_(text), pos_(position), line_(line), comment_(comment) {}

    // The next token; empty at the end of the text.
    std::string_view next() {
        skip(true);
        const std::size_t start = pos_;
        while (pos_ < text_.size() && !isSpace(text_[pos_]) && text_[pos_] != comment_) ++pos_;
        return text_.substr(start, pos_ - start);
    }
    // The next token on the current line; empty at the end of the line.
    std::string_view nextOnLine() {
        skip(false);
        if (pos_ < text_.size() && text_[pos_] == '\n') return {};
        return next();
    }
    // Moves past the end of the current line (the rest of it is ignored).
    void endLine() {
        while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
    }
    // True when only whitespace and comments are left.
    bool atEnd() {
        skip(true);
        return pos_ >= text_.size();
    }
    int line() const { return line_; }
    std::size_t remaining() const { return text_.size() - pos_; }

private:
    void skip(bool newlines) {
        while (pos_ < text_.size()) {
            const char c = text_[pos_];
            if (comment_ && c == comment_) {
                while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
            } else if (c == '\n') {
                if (!newlines) return;
                ++line_, ++pos_;
            } else if (isSpace(c)) {
                ++pos_;
            } else {
                return;
            }
        }
    }

    std::string_view text_;
    std::size_t pos_;
    int line_;
    char comment_;
};

} // namespace mag::meshText
