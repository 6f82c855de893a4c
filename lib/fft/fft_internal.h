/* SPDX-License-Identifier: MIT */
/* Private to lib/fft: instance set-up shared by the per-length init functions. */
#ifndef SBR_FFT_INTERNAL_H
#define SBR_FFT_INTERNAL_H

#include "sbr/fft.h"
#include "fft_tables.h"

/* Integrity word seed; a zeroed or overwritten instance fails the seal. */
#define SBR_FFT_CHECK_KEY 0x5B2F0F70u

sbr_status_t sbr_fft_priv_setup(sbr_fft_t *fft, uint32_t n, const uint16_t *bitrev,
                                const sbr_complex_t *tw0, const sbr_complex_t *tw1,
                                const sbr_complex_t *tw2, const sbr_complex_t *tw3);

/* The integrity word of an instance: every field mixed in (length, stages and the table
   addresses), so an instance with any field overwritten is refused before a table is
   read; computed from the fields alone, so an image keeps only the tables it uses. */
uint32_t sbr_fft_priv_seal(const sbr_fft_t *fft);

#endif /* SBR_FFT_INTERNAL_H */
