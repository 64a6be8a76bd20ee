#include <magFoam/InputFile.hpp>

#include <magFoam/Error.hpp>

#include <fstream>

namespace mag {

namespace fs = std::filesystem;

namespace {

std::string kindOf(const fs::file_status& status) {
    switch (status.type()) {
    case fs::file_type::directory: return "a directory";
    case fs::file_type::fifo: return "a FIFO (named pipe)";
    case fs::file_type::character: return "a character device";
    case fs::file_type::block: return "a block device";
    case fs::file_type::socket: return "a socket";
    default: return "not a regular file";
    }
}

} // namespace

bool inputPresent(const fs::path& file) {
    std::error_code ec;
    return fs::symlink_status(file, ec).type() != fs::file_type::not_found && !ec;
}

std::size_t checkInputFile(const fs::path& file, std::size_t limit, const std::string& what) {
    const std::string name = file.string();
    std::error_code ec;
    const fs::file_status link = fs::symlink_status(file, ec);
    if (ec || link.type() == fs::file_type::not_found) throw InputError(name + ": file not found");
    const fs::file_status status = fs::status(file, ec);  // follows links
    if (status.type() == fs::file_type::not_found)
        throw InputError(name + ": file not found (a link to a missing file)");
    if (status.type() != fs::file_type::regular)
        throw InputError(name + ": is " + kindOf(status) + ", expected a regular " + what);
    const auto size = fs::file_size(file, ec);
    if (!ec && size > limit)
        throw InputError(name + ": " + what + " of " + std::to_string(size) + " bytes is above the limit of " +
                         std::to_string(limit) + " bytes");
    return ec ? 0 : static_cast<std::size_t>(size);
}

std::string readInputFile(const fs::path& file, std::size_t limit, const std::string& what) {
    const std::string name = file.string();
    checkInputFile(file, limit, what);
    std::ifstream in(file, std::ios::binary);
    if (!in) throw InputError(name + ": cannot open the " + what + " (no permission to read?)");
    // Read at most limit + 1 bytes: a file that grows while it is read is caught too.
    std::string bytes;
    char buffer[1 << 16];
    while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
        bytes.append(buffer, static_cast<std::size_t>(in.gcount()));
        if (bytes.size() > limit)
            throw InputError(name + ": " + what + " is above the limit of " + std::to_string(limit) + " bytes");
    }
    if (in.bad()) throw InputError(name + ": reading the " + what + " failed");
    return bytes;
}

} // namespace mag
