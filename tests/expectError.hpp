// Test helpers for bad input: the message of the InputError a call throws.
#pragma once

#include <magFoam/Error.hpp>

#include <catch2/catch.hpp>

#include <string>

namespace magtest {

// Runs f, expects an InputError, returns its message (fails the test case
// when f throws none).
template <class F> std::string inputErrorOf(F&& f) {
    try {
        f();
    } catch (const mag::InputError& e) {
        return e.what();
    }
    FAIL("expected an InputError");
    return {};
}

inline bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

} // namespace magtest
