// Exceptions. Every error a user can cause is an InputError that names where it
// happened (file, line, column, key or mesh element) and what was expected.
#pragma once

#include <stdexcept>
#include <string>

namespace mag {

// Bad user input: malformed or invalid dictionaries, unusable meshes, unknown
// model names. Apps catch it, print what() and exit non-zero.
class InputError : public std::runtime_error {
public:
    explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

// A file that cannot be written (full disk, no permission, a folder gone):
// names the file and the system's reason (OutputFile.hpp).
class OutputError : public std::runtime_error {
public:
    explicit OutputError(const std::string& message) : std::runtime_error(message) {}
};

// A state the simulation must not continue from (NaN/inf in a body's state).
class StateError : public std::runtime_error {
public:
    explicit StateError(const std::string& message) : std::runtime_error(message) {}
};

} // namespace mag
