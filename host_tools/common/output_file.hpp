// SPDX-License-Identifier: MIT
// Output files that never cost a user an earlier result: each is written under a
// temporary name in its own folder and renamed over the target only when the whole file
// has been written and closed without error. A run that fails (or is killed) leaves the
// earlier file as it was; a failed write is reported with the path.
#pragma once

#include <fstream>
#include <string>

namespace sbr_host {

// The temporary name of `path` in its folder, keeping the extension (an image writer
// picks its format by it): "dir/name.tmp-PID.ext".
std::string temp_path_of(const std::string &path);

// Renames `tmp` over `path`; "" on success, else why (the temporary removed).
std::string commit_temp(const std::string &tmp, const std::string &path);

// Whether `path` can be written: its temporary is created and removed. "" when it can,
// else the reason ("a folder", "No such file or directory", ...).
std::string probe_writable(const std::string &path);

class OutputFile {
public:
    OutputFile() = default;
    OutputFile(const OutputFile &) = delete;
    OutputFile &operator=(const OutputFile &) = delete;
    ~OutputFile();  // an uncommitted temporary is removed
    // Opens the temporary of `path`; "" on success, else why.
    std::string open(const std::string &path);
    bool is_open() const { return s_.is_open(); }
    template <class T>
    OutputFile &operator<<(const T &v) {
        s_ << v;
        return *this;
    }
    const std::string &path() const { return path_; }
    // Flushes, closes and renames over the target; "" on success, else why.
    std::string commit();

private:
    std::ofstream s_;
    std::string path_, tmp_;
};

}  // namespace sbr_host
