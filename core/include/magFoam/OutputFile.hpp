// Checked output (docs/architecture.md#output-files). Every byte the apps
// write goes through here, so that a write that fails (full disk, a folder
// removed, no permission) stops the app with an OutputError naming the file
// and the system's reason, instead of leaving a cut file behind a success.
//
// Whole files are written to "<name>.tmp" and renamed over the old one: a
// crash at any moment leaves the old file or the new one, never half of it.
// Files that grow (the CSVs) grow by whole rows; a row cut by a crash or a
// full disk is the file's last, unterminated line, which readers of the file
// after a restart drop (cutCsvAfter).
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace mag {

// Create `folder` and its parents; OutputError when it cannot.
void makeFolder(const std::filesystem::path& folder);

// Write `text` as the whole of `file`, through a temporary and a rename.
void writeFileAtomically(const std::filesystem::path& file, std::string_view text);

// Keep the header and the complete rows whose first column (a time) is at
// most tMax (+1e-12): a restart's CSV files end at the restart time. An
// unterminated last row (a cut write) is dropped. Rewritten atomically;
// nothing happens when the file does not exist.
void cutCsvAfter(const std::filesystem::path& file, double tMax);

// A file written row by row (CSV): each append() goes to the file at once
// (rows stay readable while the run goes on) and is checked.
class AppendedFile {
public:
    AppendedFile() = default;
    // keep: append to an existing file (a restart); otherwise start it anew.
    // The header is written when the file is started.
    AppendedFile(const std::filesystem::path& file, std::string_view header, bool keep);
    AppendedFile(AppendedFile&& other) noexcept;
    AppendedFile& operator=(AppendedFile&& other) noexcept;
    AppendedFile(const AppendedFile&) = delete;
    AppendedFile& operator=(const AppendedFile&) = delete;
    ~AppendedFile();

    bool isOpen() const { return fd_ >= 0; }
    void append(std::string_view text);

private:
    std::filesystem::path path_;
    int fd_ = -1;
};

} // namespace mag
