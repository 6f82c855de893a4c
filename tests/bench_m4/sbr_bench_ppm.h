/* SPDX-License-Identifier: MIT */
/* The bench images' PPM header reader (semihosted stdio): one decimal token, skipping
   white space and # comments. A bench helper, not part of the core. */
#ifndef SBR_BENCH_PPM_H
#define SBR_BENCH_PPM_H

#include <stdint.h>
#include <stdio.h>

/* The next token of a PPM header as a number (at most 9 digits); 0 when there is none. */
static inline int read_token(FILE *f, uint32_t *v)
{
    int ch = fgetc(f);
    uint32_t x = 0u;
    int digits = 0;
    while ((ch == ' ') || (ch == '\n') || (ch == '\r') || (ch == '\t') || (ch == '#')) {
        if (ch == '#') {
            while ((ch != '\n') && (ch != EOF)) {
                ch = fgetc(f);
            }
        }
        ch = fgetc(f);
    }
    while ((ch >= '0') && (ch <= '9') && (digits < 9)) {
        x = x * 10u + (uint32_t)(ch - '0');
        digits++;
        ch = fgetc(f);
    }
    *v = x;
    return digits > 0;
}

#endif /* SBR_BENCH_PPM_H */
