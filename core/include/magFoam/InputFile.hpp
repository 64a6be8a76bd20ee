// Reading a user's input file (dictionary, mesh) whole into memory, with the
// checks every reader needs first: it is a regular file (a FIFO would block
// forever, a link to /dev/zero never ends) and it is not larger than the limit
// for its kind (a mistaken or hostile file must not exhaust the memory).
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

namespace mag {

// Limits of readInputFile for the two kinds of input.
inline constexpr std::size_t dictionaryFileLimit = std::size_t(64) << 20;  // 64 MiB
inline constexpr std::size_t meshFileLimit = std::size_t(1) << 30;         // 1 GiB

// Whether anything is at `file`, a dangling link included: an optional input
// that is present is read, so a broken link is an error, not "no such input".
bool inputPresent(const std::filesystem::path& file);

// The checks of readInputFile without reading (for readers that open the file
// themselves); returns the file size.
std::size_t checkInputFile(const std::filesystem::path& file, std::size_t limit, const std::string& what);

// The bytes of `file`. InputError naming the file when it does not exist (a
// dangling link included), is a directory or not a regular file (FIFO, device,
// socket), cannot be read, or holds more than `limit` bytes ("file not found"
// and "is a FIFO (named pipe), expected a regular dictionary", for example). `what` names the
// kind of file in messages ("dictionary", "mesh file").
std::string readInputFile(const std::filesystem::path& file, std::size_t limit, const std::string& what);

} // namespace mag
