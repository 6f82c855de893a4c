// SPDX-License-Identifier: MIT
// For the host test programs: -h / --help says what the program tests and how to call it
// (exit 0), and an option the program does not take is an error naming it (exit 2),
// never read as a path or ignored.
#pragma once
#include <cstdio>
#include <cstring>

// -1: go on; otherwise the exit status. `options`: the options the program takes (each
// followed by a value), nullptr-terminated, or nullptr for none.
inline int test_help(int argc, char **argv, const char *about, const char *usage,
                     const char *const *options = nullptr) {
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (std::strcmp(a, "-h") == 0 || std::strcmp(a, "--help") == 0) {
            std::printf("%s\nusage: %s\n", about, usage);
            return 0;
        }
        if (a[0] != '-' || a[1] == '\0') continue;
        bool known = false;
        for (const char *const *o = options; o != nullptr && *o != nullptr; ++o)
            if (std::strcmp(a, *o) == 0) known = true;
        if (!known) {
            std::fprintf(stderr, "%s: unknown option '%s' (usage: %s)\n", argv[0], a, usage);
            return 2;
        }
        ++i;  // its value
    }
    return -1;
}
