#include "magFoam/OutputFile.hpp"

#include "magFoam/Error.hpp"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <unistd.h>

namespace mag {

namespace {

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& what, int error) {
    throw OutputError(file.string() + ": " + what + " (" + std::strerror(error) + ")");
}

// write(2) until everything is out: it may take part of a buffer at a time.
void writeAll(int fd, std::string_view text, const std::filesystem::path& file) {
    while (!text.empty()) {
        const ssize_t n = ::write(fd, text.data(), text.size());
        if (n < 0) {
            if (errno == EINTR) continue;
            fail(file, "cannot write", errno);
        }
        text.remove_prefix(static_cast<std::size_t>(n));
    }
}

} // namespace

void makeFolder(const std::filesystem::path& folder) {
    std::error_code ec;
    std::filesystem::create_directories(folder, ec);
    if (ec) throw OutputError(folder.string() + ": cannot create the folder (" + ec.message() + ")");
}

void writeFileAtomically(const std::filesystem::path& file, std::string_view text) {
    if (file.has_parent_path()) makeFolder(file.parent_path());
    std::filesystem::path tmp = file;
    tmp += ".tmp";
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) fail(tmp, "cannot open for writing", errno);
    try {
        writeAll(fd, text, tmp);
    } catch (...) {
        ::close(fd);
        ::unlink(tmp.c_str());  // a cut temporary helps nobody and holds the disk
        throw;
    }
    // close() reports write-back errors some file systems defer (NFS, quotas).
    if (::close(fd) != 0) {
        const int error = errno;
        ::unlink(tmp.c_str());
        fail(tmp, "cannot write", error);
    }
    if (::rename(tmp.c_str(), file.c_str()) != 0) {
        const int error = errno;
        ::unlink(tmp.c_str());
        fail(file, "cannot replace the file", error);
    }
}

void cutCsvAfter(const std::filesystem::path& file, double tMax) {
    std::ifstream in(file, std::ios::binary);
    if (!in) return;
    const std::string all((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::string kept;
    std::size_t pos = 0;
    bool header = true;
    while (pos < all.size()) {
        const std::size_t end = all.find('\n', pos);
        if (end == std::string::npos) break;  // a cut last row
        const std::string_view row(all.data() + pos, end - pos + 1);
        if (header || std::strtod(row.data(), nullptr) <= tMax + 1e-12) kept += row;
        header = false;
        pos = end + 1;
    }
    writeFileAtomically(file, kept);
}

AppendedFile::AppendedFile(const std::filesystem::path& file, std::string_view header, bool keep) : path_(file) {
    if (file.has_parent_path()) makeFolder(file.parent_path());
    const bool fresh = !keep || !std::filesystem::exists(file);
    fd_ = ::open(file.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC | (fresh ? O_TRUNC : O_APPEND), 0644);
    if (fd_ < 0) fail(file, "cannot open for writing", errno);
    if (fresh) append(std::string(header) + "\n");
}

AppendedFile::AppendedFile(AppendedFile&& other) noexcept : path_(std::move(other.path_)), fd_(other.fd_) {
    other.fd_ = -1;
}

AppendedFile& AppendedFile::operator=(AppendedFile&& other) noexcept {
    if (this != &other) {
        if (fd_ >= 0) ::close(fd_);
        path_ = std::move(other.path_);
        fd_ = other.fd_;
        other.fd_ = -1;
    }
    return *this;
}

AppendedFile::~AppendedFile() {
    if (fd_ >= 0) ::close(fd_);
}

void AppendedFile::append(std::string_view text) {
    if (fd_ < 0) throw OutputError(path_.string() + ": not open for writing");
    writeAll(fd_, text, path_);
}

} // namespace mag
