// SPDX-License-Identifier: MIT
#include "output_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include <unistd.h>

namespace fs = std::filesystem;

namespace sbr_host {

std::string temp_path_of(const std::string &path) {
    const fs::path p(path);
    fs::path t = p;
    t.replace_filename(p.stem().string() + ".tmp-" + std::to_string(getpid()) + p.extension().string());
    return t.string();
}

std::string commit_temp(const std::string &tmp, const std::string &path) {
    std::error_code ec;
    if (fs::is_directory(path, ec)) {
        fs::remove(tmp, ec);
        return "a folder, not a file";
    }
    fs::rename(tmp, path, ec);
    if (ec) {
        std::error_code ec2;
        fs::remove(tmp, ec2);
        return ec.message();
    }
    return "";
}

std::string probe_writable(const std::string &path) {
    std::error_code ec;
    if (fs::is_directory(path, ec)) return "a folder, not a file";
    const std::string tmp = temp_path_of(path);
    std::FILE *f = std::fopen(tmp.c_str(), "wb");
    if (f == nullptr) return std::strerror(errno);
    std::fclose(f);
    fs::remove(tmp, ec);
    return "";
}

OutputFile::~OutputFile() {
    if (!tmp_.empty()) {
        if (s_.is_open()) s_.close();
        std::error_code ec;
        fs::remove(tmp_, ec);
    }
}

std::string OutputFile::open(const std::string &path) {
    path_ = path;
    std::error_code ec;
    if (fs::is_directory(path, ec)) return "a folder, not a file";
    tmp_ = temp_path_of(path);
    errno = 0;
    s_.open(tmp_, std::ios::out | std::ios::trunc | std::ios::binary);
    if (!s_) {
        const std::string why = errno != 0 ? std::strerror(errno) : "cannot be created";
        tmp_.clear();
        return why;
    }
    return "";
}

std::string OutputFile::commit() {
    if (tmp_.empty()) return "not open";
    s_.flush();
    const bool good = static_cast<bool>(s_);
    s_.close();
    if (!good || s_.fail()) {
        std::error_code ec;
        fs::remove(tmp_, ec);
        tmp_.clear();
        return "a write failed (disk full?)";
    }
    const std::string why = commit_temp(tmp_, path_);
    tmp_.clear();
    return why;
}

}  // namespace sbr_host
