/* SPDX-License-Identifier: MIT */
/* Channel maps (include/sbr/map.h): the u8 intensity and chromaticity maps of a frame,
   with optional block subsampling. */
#include "sbr/map.h"
#include "sbr/map.h"

#include "../common/sbr_util.h"

/* Tone curve applied to the channel values before the intensity formula (map.h): square-root
   compression, tone[c] = the integer nearest the square root of 255 c. It stretches the
   dark end (0..64 become 0..128) so that a sign in shadow under a bright sky spans enough
   grey levels for MSER's stability test. Computed offline; test_mser checks every entry
   against the definition in integer arithmetic. */
static const uint8_t k_tone[256] = {
    0u, 16u, 23u, 28u, 32u, 36u, 39u, 42u, 45u, 48u, 50u, 53u, 55u, 58u,
    60u, 62u, 64u, 66u, 68u, 70u, 71u, 73u, 75u, 77u, 78u, 80u, 81u, 83u,
    84u, 86u, 87u, 89u, 90u, 92u, 93u, 94u, 96u, 97u, 98u, 100u, 101u, 102u,
    103u, 105u, 106u, 107u, 108u, 109u, 111u, 112u, 113u, 114u, 115u, 116u, 117u, 118u,
    119u, 121u, 122u, 123u, 124u, 125u, 126u, 127u, 128u, 129u, 130u, 131u, 132u, 133u,
    134u, 135u, 135u, 136u, 137u, 138u, 139u, 140u, 141u, 142u, 143u, 144u, 145u, 145u,
    146u, 147u, 148u, 149u, 150u, 151u, 151u, 152u, 153u, 154u, 155u, 156u, 156u, 157u,
    158u, 159u, 160u, 160u, 161u, 162u, 163u, 164u, 164u, 165u, 166u, 167u, 167u, 168u,
    169u, 170u, 170u, 171u, 172u, 173u, 173u, 174u, 175u, 176u, 176u, 177u, 178u, 179u,
    179u, 180u, 181u, 181u, 182u, 183u, 183u, 184u, 185u, 186u, 186u, 187u, 188u, 188u,
    189u, 190u, 190u, 191u, 192u, 192u, 193u, 194u, 194u, 195u, 196u, 196u, 197u, 198u,
    198u, 199u, 199u, 200u, 201u, 201u, 202u, 203u, 203u, 204u, 204u, 205u, 206u, 206u,
    207u, 208u, 208u, 209u, 209u, 210u, 211u, 211u, 212u, 212u, 213u, 214u, 214u, 215u,
    215u, 216u, 217u, 217u, 218u, 218u, 219u, 220u, 220u, 221u, 221u, 222u, 222u, 223u,
    224u, 224u, 225u, 225u, 226u, 226u, 227u, 228u, 228u, 229u, 229u, 230u, 230u, 231u,
    231u, 232u, 233u, 233u, 234u, 234u, 235u, 235u, 236u, 236u, 237u, 237u, 238u, 238u,
    239u, 240u, 240u, 241u, 241u, 242u, 242u, 243u, 243u, 244u, 244u, 245u, 245u, 246u,
    246u, 247u, 247u, 248u, 248u, 249u, 249u, 250u, 250u, 251u, 251u, 252u, 252u, 253u,
    253u, 254u, 254u, 255u
};

/* Colour map value from raw mean channel values: 128 + 128 d / (R + G + B + SBR_MAP_DARK),
   d = the colour difference of the kind (map.h), the quotient truncated towards zero, the
   result clamped to 0..255. */
#define SBR_MAP_DARK 60
static uint8_t chroma_value(int32_t d, uint32_t sum)
{
    int32_t v = 128 + ((128 * d) / ((int32_t)sum + SBR_MAP_DARK));
    if (v < 0) {
        v = 0;
    }
    if (v > 255) {
        v = 255;
    }
    return (uint8_t)v;
}

/* One map value from mean channel values. */
static uint8_t map_value(sbr_map_kind_t kind, uint32_t mr, uint32_t mg, uint32_t mb)
{
    const uint32_t ur = mr & 255u;
    const uint32_t ug = mg & 255u;
    const uint32_t ub = mb & 255u;
    const int32_t r = (int32_t)ur;
    const int32_t g = (int32_t)ug;
    const int32_t b = (int32_t)ub;
    const uint32_t sum = (ur + ug) + ub;
    uint8_t v;
    switch (kind) {
    case SBR_MAP_RED:
        v = chroma_value(((2 * r) - g) - b, sum);
        break;
    case SBR_MAP_BLUE:
        v = chroma_value(((2 * b) - r) - g, sum);
        break;
    case SBR_MAP_YELLOW:
        v = chroma_value((r + g) - (2 * b), sum);
        break;
    default:
        v = (uint8_t)(((uint32_t)k_tone[ur] + (uint32_t)k_tone[ug] + (uint32_t)k_tone[ub] + 1u) / 3u);
        break;
    }
    return v;
}

/* One row of the red map whose pixels with a colour difference d <= 0 (value at most
   128) get 128: map_make() for sbr_map_make_bright(). */
static inline uint8_t red_bright(const uint8_t *px, uint32_t ri, uint32_t bi)
{
    const uint32_t ur = (uint32_t)px[ri];
    const uint32_t ug = (uint32_t)px[1];
    const uint32_t ub = (uint32_t)px[bi];
    const int32_t d = ((2 * (int32_t)ur) - (int32_t)ug) - (int32_t)ub;
    return (d > 0) ? chroma_value(d, (ur + ug) + ub) : 128u;
}

static void map_row_red_bright(const uint8_t *row, uint32_t ri, uint32_t bi, uint32_t n,
                               uint8_t *dst)
{
    const uint32_t n4 = n - (n % 4u);
    uint32_t x;
    for (x = 0u; x < n4; x += 4u) {
        /* four pixels a step: the loop's own work shared */
        const uint8_t *px = &row[x * 3u];
        dst[x] = red_bright(px, ri, bi);
        dst[x + 1u] = red_bright(&px[3], ri, bi);
        dst[x + 2u] = red_bright(&px[6], ri, bi);
        dst[x + 3u] = red_bright(&px[9], ri, bi);
    }
    for (x = n4; x < n; x++) {
        dst[x] = red_bright(&row[x * 3u], ri, bi);
    }
}

/* map_value(SBR_MAP_INTENSITY, ...) of one colour pixel (symmetric in its channels). */

static inline uint8_t intensity3(const uint8_t *px)
{
    /* (s + 1) / 3 for the sum s of three tone values (0..765): the intensity's rounding
       division as one load. test_map checks the maps against map.h's formula. */
    static const uint8_t k_third[766] = {
        0u, 0u, 1u, 1u, 1u, 2u, 2u, 2u, 3u, 3u, 3u, 4u, 4u, 4u, 5u, 5u,
        5u, 6u, 6u, 6u, 7u, 7u, 7u, 8u, 8u, 8u, 9u, 9u, 9u, 10u, 10u, 10u,
        11u, 11u, 11u, 12u, 12u, 12u, 13u, 13u, 13u, 14u, 14u, 14u, 15u, 15u, 15u, 16u,
        16u, 16u, 17u, 17u, 17u, 18u, 18u, 18u, 19u, 19u, 19u, 20u, 20u, 20u, 21u, 21u,
        21u, 22u, 22u, 22u, 23u, 23u, 23u, 24u, 24u, 24u, 25u, 25u, 25u, 26u, 26u, 26u,
        27u, 27u, 27u, 28u, 28u, 28u, 29u, 29u, 29u, 30u, 30u, 30u, 31u, 31u, 31u, 32u,
        32u, 32u, 33u, 33u, 33u, 34u, 34u, 34u, 35u, 35u, 35u, 36u, 36u, 36u, 37u, 37u,
        37u, 38u, 38u, 38u, 39u, 39u, 39u, 40u, 40u, 40u, 41u, 41u, 41u, 42u, 42u, 42u,
        43u, 43u, 43u, 44u, 44u, 44u, 45u, 45u, 45u, 46u, 46u, 46u, 47u, 47u, 47u, 48u,
        48u, 48u, 49u, 49u, 49u, 50u, 50u, 50u, 51u, 51u, 51u, 52u, 52u, 52u, 53u, 53u,
        53u, 54u, 54u, 54u, 55u, 55u, 55u, 56u, 56u, 56u, 57u, 57u, 57u, 58u, 58u, 58u,
        59u, 59u, 59u, 60u, 60u, 60u, 61u, 61u, 61u, 62u, 62u, 62u, 63u, 63u, 63u, 64u,
        64u, 64u, 65u, 65u, 65u, 66u, 66u, 66u, 67u, 67u, 67u, 68u, 68u, 68u, 69u, 69u,
        69u, 70u, 70u, 70u, 71u, 71u, 71u, 72u, 72u, 72u, 73u, 73u, 73u, 74u, 74u, 74u,
        75u, 75u, 75u, 76u, 76u, 76u, 77u, 77u, 77u, 78u, 78u, 78u, 79u, 79u, 79u, 80u,
        80u, 80u, 81u, 81u, 81u, 82u, 82u, 82u, 83u, 83u, 83u, 84u, 84u, 84u, 85u, 85u,
        85u, 86u, 86u, 86u, 87u, 87u, 87u, 88u, 88u, 88u, 89u, 89u, 89u, 90u, 90u, 90u,
        91u, 91u, 91u, 92u, 92u, 92u, 93u, 93u, 93u, 94u, 94u, 94u, 95u, 95u, 95u, 96u,
        96u, 96u, 97u, 97u, 97u, 98u, 98u, 98u, 99u, 99u, 99u, 100u, 100u, 100u, 101u, 101u,
        101u, 102u, 102u, 102u, 103u, 103u, 103u, 104u, 104u, 104u, 105u, 105u, 105u, 106u, 106u, 106u,
        107u, 107u, 107u, 108u, 108u, 108u, 109u, 109u, 109u, 110u, 110u, 110u, 111u, 111u, 111u, 112u,
        112u, 112u, 113u, 113u, 113u, 114u, 114u, 114u, 115u, 115u, 115u, 116u, 116u, 116u, 117u, 117u,
        117u, 118u, 118u, 118u, 119u, 119u, 119u, 120u, 120u, 120u, 121u, 121u, 121u, 122u, 122u, 122u,
        123u, 123u, 123u, 124u, 124u, 124u, 125u, 125u, 125u, 126u, 126u, 126u, 127u, 127u, 127u, 128u,
        128u, 128u, 129u, 129u, 129u, 130u, 130u, 130u, 131u, 131u, 131u, 132u, 132u, 132u, 133u, 133u,
        133u, 134u, 134u, 134u, 135u, 135u, 135u, 136u, 136u, 136u, 137u, 137u, 137u, 138u, 138u, 138u,
        139u, 139u, 139u, 140u, 140u, 140u, 141u, 141u, 141u, 142u, 142u, 142u, 143u, 143u, 143u, 144u,
        144u, 144u, 145u, 145u, 145u, 146u, 146u, 146u, 147u, 147u, 147u, 148u, 148u, 148u, 149u, 149u,
        149u, 150u, 150u, 150u, 151u, 151u, 151u, 152u, 152u, 152u, 153u, 153u, 153u, 154u, 154u, 154u,
        155u, 155u, 155u, 156u, 156u, 156u, 157u, 157u, 157u, 158u, 158u, 158u, 159u, 159u, 159u, 160u,
        160u, 160u, 161u, 161u, 161u, 162u, 162u, 162u, 163u, 163u, 163u, 164u, 164u, 164u, 165u, 165u,
        165u, 166u, 166u, 166u, 167u, 167u, 167u, 168u, 168u, 168u, 169u, 169u, 169u, 170u, 170u, 170u,
        171u, 171u, 171u, 172u, 172u, 172u, 173u, 173u, 173u, 174u, 174u, 174u, 175u, 175u, 175u, 176u,
        176u, 176u, 177u, 177u, 177u, 178u, 178u, 178u, 179u, 179u, 179u, 180u, 180u, 180u, 181u, 181u,
        181u, 182u, 182u, 182u, 183u, 183u, 183u, 184u, 184u, 184u, 185u, 185u, 185u, 186u, 186u, 186u,
        187u, 187u, 187u, 188u, 188u, 188u, 189u, 189u, 189u, 190u, 190u, 190u, 191u, 191u, 191u, 192u,
        192u, 192u, 193u, 193u, 193u, 194u, 194u, 194u, 195u, 195u, 195u, 196u, 196u, 196u, 197u, 197u,
        197u, 198u, 198u, 198u, 199u, 199u, 199u, 200u, 200u, 200u, 201u, 201u, 201u, 202u, 202u, 202u,
        203u, 203u, 203u, 204u, 204u, 204u, 205u, 205u, 205u, 206u, 206u, 206u, 207u, 207u, 207u, 208u,
        208u, 208u, 209u, 209u, 209u, 210u, 210u, 210u, 211u, 211u, 211u, 212u, 212u, 212u, 213u, 213u,
        213u, 214u, 214u, 214u, 215u, 215u, 215u, 216u, 216u, 216u, 217u, 217u, 217u, 218u, 218u, 218u,
        219u, 219u, 219u, 220u, 220u, 220u, 221u, 221u, 221u, 222u, 222u, 222u, 223u, 223u, 223u, 224u,
        224u, 224u, 225u, 225u, 225u, 226u, 226u, 226u, 227u, 227u, 227u, 228u, 228u, 228u, 229u, 229u,
        229u, 230u, 230u, 230u, 231u, 231u, 231u, 232u, 232u, 232u, 233u, 233u, 233u, 234u, 234u, 234u,
        235u, 235u, 235u, 236u, 236u, 236u, 237u, 237u, 237u, 238u, 238u, 238u, 239u, 239u, 239u, 240u,
        240u, 240u, 241u, 241u, 241u, 242u, 242u, 242u, 243u, 243u, 243u, 244u, 244u, 244u, 245u, 245u,
        245u, 246u, 246u, 246u, 247u, 247u, 247u, 248u, 248u, 248u, 249u, 249u, 249u, 250u, 250u, 250u,
        251u, 251u, 251u, 252u, 252u, 252u, 253u, 253u, 253u, 254u, 254u, 254u, 255u, 255u
    };
    return k_third[((uint32_t)k_tone[px[0]] + (uint32_t)k_tone[px[1]]) + (uint32_t)k_tone[px[2]]];
}

/* One row at subsample 1: map_value() of each pixel, without the block means' divisions;
   one loop per kind (the same formulas as map_value(), the choice made once per row). */
static void map_row(sbr_map_kind_t kind, const uint8_t *row, uint32_t bpp, uint32_t ri,
                    uint32_t bi, uint32_t n, uint8_t *dst)
{
    uint32_t x;
    if (bpp == 1u) {
        for (x = 0u; x < n; x++) {
            dst[x] = k_tone[row[x]];
        }
    } else if (kind == SBR_MAP_RED) {
        for (x = 0u; x < n; x++) {
            const uint8_t *px = &row[x * 3u];
            dst[x] = map_value(SBR_MAP_RED, px[ri], px[1], px[bi]);
        }
    } else if (kind == SBR_MAP_BLUE) {
        for (x = 0u; x < n; x++) {
            const uint8_t *px = &row[x * 3u];
            dst[x] = map_value(SBR_MAP_BLUE, px[ri], px[1], px[bi]);
        }
    } else if (kind == SBR_MAP_YELLOW) {
        for (x = 0u; x < n; x++) {
            const uint8_t *px = &row[x * 3u];
            dst[x] = map_value(SBR_MAP_YELLOW, px[ri], px[1], px[bi]);
        }
    } else {
        const uint32_t n4 = n - (n % 4u);
        for (x = 0u; x < n4; x += 4u) {
            /* four pixels a step: the loop's own work shared */
            const uint8_t *px = &row[x * 3u];
            dst[x] = intensity3(px);
            dst[x + 1u] = intensity3(&px[3]);
            dst[x + 2u] = intensity3(&px[6]);
            dst[x + 3u] = intensity3(&px[9]);
        }
        for (x = n4; x < n; x++) {
            dst[x] = intensity3(&row[x * 3u]);
        }
    }
}


/* Rounded block mean s / n2: a shift when n2 is a power of two (shift = log2 n2, else 0),
   the same value as the division. */
static uint32_t block_mean(uint32_t s, uint32_t n2, uint32_t shift)
{
    uint32_t m;
    if (shift != 0u) {
        m = (s + (n2 / 2u)) >> shift;
    } else {
        m = (s + (n2 / 2u)) / n2;
    }
    return m;
}

/* How one source pixel is read: bytes per pixel and the red and blue channel offsets;
   and the block of a subsampled output pixel (n2 = subsample^2 pixels, shift = log2 n2
   when n2 is a power of two, else 0). */
typedef struct map_read_s {
    uint32_t bpp;
    uint32_t ri;
    uint32_t bi;
    uint32_t sub;
    uint32_t n2;
    uint32_t shift;
} map_read_t;

/* The rounded means of one 2 x 2 block's channels (a: its top row's pixels, b: the
   bottom row's; ri, bi: the red and blue offsets). */
static inline void block2_means(const uint8_t *a, const uint8_t *b, uint32_t ri, uint32_t bi,
                                uint32_t mean[3])
{
    const uint32_t sr = (((uint32_t)a[ri] + (uint32_t)a[3u + ri]) + (uint32_t)b[ri]) +
                        (uint32_t)b[3u + ri];
    const uint32_t sg = (((uint32_t)a[1] + (uint32_t)a[4]) + (uint32_t)b[1]) + (uint32_t)b[4];
    const uint32_t sb = (((uint32_t)a[bi] + (uint32_t)a[3u + bi]) + (uint32_t)b[bi]) +
                        (uint32_t)b[3u + bi];
    mean[0] = (sr + 2u) >> 2u;
    mean[1] = (sg + 2u) >> 2u;
    mean[2] = (sb + 2u) >> 2u;
}

/* Output row y of a map at subsample 2 from a colour frame (the recogniser's blue map):
   the same block means as map_block_row(), the four pixels of a block read directly; the
   blue map's loop with its kind fixed (so that map_value() is inlined there). */
static void map_block2_row(const sbr_image_t *src, sbr_map_kind_t kind, const map_read_t *rd,
                           uint32_t y, uint32_t ow, uint8_t *dst)
{
    const uint8_t *r0 = &src->data[((size_t)y * 2u) * src->stride];
    const uint8_t *r1 = &r0[src->stride];
    const uint32_t ri = rd->ri;
    const uint32_t bi = rd->bi;
    uint32_t x;
    uint32_t m[3];
    if (kind == SBR_MAP_BLUE) {
        for (x = 0u; x < ow; x++) {
            block2_means(&r0[(size_t)x * 6u], &r1[(size_t)x * 6u], ri, bi, m);
            dst[x] = map_value(SBR_MAP_BLUE, m[0], m[1], m[2]);
        }
    } else {
        for (x = 0u; x < ow; x++) {
            block2_means(&r0[(size_t)x * 6u], &r1[(size_t)x * 6u], ri, bi, m);
            dst[x] = map_value(kind, m[0], m[1], m[2]);
        }
    }
}

/* Output row y of a subsampled map: each pixel the map value of its block's mean colour. */
static void map_block_row(const sbr_image_t *src, sbr_map_kind_t kind, const map_read_t *rd,
                          uint32_t y, uint32_t ow, uint8_t *dst)
{
    uint32_t x;
    for (x = 0u; x < ow; x++) {
        uint32_t sr = 0u;
        uint32_t sg = 0u;
        uint32_t sb = 0u;
        uint32_t by;
        uint32_t bx;
        for (by = 0u; by < rd->sub; by++) {
            const uint8_t *row = &src->data[(((size_t)y * rd->sub) + by) * src->stride];
            for (bx = 0u; bx < rd->sub; bx++) {
                const uint8_t *px = &row[(((size_t)x * rd->sub) + bx) * rd->bpp];
                if (rd->bpp == 1u) {
                    sr += px[0];
                    sg += px[0];
                    sb += px[0];
                } else {
                    sr += px[rd->ri];
                    sg += px[1];
                    sb += px[rd->bi];
                }
            }
        }
        dst[x] = map_value(kind, block_mean(sr, rd->n2, rd->shift),
                           block_mean(sg, rd->n2, rd->shift), block_mean(sb, rd->n2, rd->shift));
    }
}

/* sbr_map_make(); bright != 0: sbr_map_make_bright(). */
static sbr_status_t map_make(const sbr_image_t *src, sbr_map_kind_t kind, uint32_t subsample,
                             uint8_t *out, uint32_t out_stride, size_t out_size,
                             sbr_image_t *out_view, int bright)
{
    sbr_status_t st;
    map_read_t rd;
    uint32_t ow;
    uint32_t oh;
    uint32_t y;
    size_t src_bytes;
    size_t out_bytes;

    if ((src == NULL) || (out == NULL)) {
        return SBR_ERR_NULL;
    }
    st = sbr_image_check(src);
    if (st != SBR_OK) {
        return st;
    }
    if (((uint32_t)kind > (uint32_t)SBR_MAP_YELLOW) || (subsample == 0u) ||
        (subsample > SBR_MAP_MAX_SUBSAMPLE) || (subsample > src->width) ||
        (subsample > src->height)) {
        return SBR_ERR_RANGE;
    }
    if ((src->format == SBR_PIXEL_GRAY8) && (kind != SBR_MAP_INTENSITY)) {
        return SBR_ERR_RANGE;
    }
    ow = src->width / subsample;
    oh = src->height / subsample;
    out_bytes = ((size_t)oh - 1u) * (size_t)out_stride;
    out_bytes += (size_t)ow;
    if ((out_stride < ow) || (out_size < out_bytes)) {
        return SBR_ERR_ALIGN;
    }
    rd.bpp = sbr_image_bytes_per_pixel(src->format);
    src_bytes = ((size_t)src->height - 1u) * (size_t)src->stride;
    src_bytes += (size_t)src->width * (size_t)rd.bpp;
    if (sbr_util_overlap(src->data, src_bytes, out, out_bytes) != 0) {
        return SBR_ERR_OVERLAP;
    }
    rd.ri = 0u;
    rd.bi = 2u;
    if (src->format == SBR_PIXEL_BGR888) {
        rd.ri = 2u;
        rd.bi = 0u;
    }
    rd.sub = subsample;
    rd.n2 = subsample * subsample;
    rd.shift = 0u;
    if ((rd.n2 & (rd.n2 - 1u)) == 0u) {
        while ((1u << rd.shift) < rd.n2) {
            rd.shift++;
        }
    }
    for (y = 0u; y < oh; y++) {
        if ((subsample == 1u) && (bright != 0) && (kind == SBR_MAP_RED)) {
            map_row_red_bright(&src->data[(size_t)y * src->stride], rd.ri, rd.bi, ow,
                               &out[(size_t)y * out_stride]);
        } else if (subsample == 1u) {
            map_row(kind, &src->data[(size_t)y * src->stride], rd.bpp, rd.ri, rd.bi, ow,
                    &out[(size_t)y * out_stride]);
        } else if ((subsample == 2u) && (rd.bpp == 3u)) {
            map_block2_row(src, kind, &rd, y, ow, &out[(size_t)y * out_stride]);
        } else {
            map_block_row(src, kind, &rd, y, ow, &out[(size_t)y * out_stride]);
        }
    }
    if (out_view != NULL) {
        out_view->width = ow;
        out_view->height = oh;
        out_view->stride = out_stride;
        out_view->format = SBR_PIXEL_GRAY8;
        out_view->data = out;
    }
    return SBR_OK;
}

sbr_status_t sbr_map_make(const sbr_image_t *src, sbr_map_kind_t kind, uint32_t subsample,
                          uint8_t *out, uint32_t out_stride, size_t out_size,
                          sbr_image_t *out_view)
{
    return map_make(src, kind, subsample, out, out_stride, out_size, out_view, 0);
}

sbr_status_t sbr_map_make_bright(const sbr_image_t *src, sbr_map_kind_t kind, uint32_t subsample,
                                 uint8_t *out, uint32_t out_stride, size_t out_size,
                                 sbr_image_t *out_view)
{
    return map_make(src, kind, subsample, out, out_stride, out_size, out_view, 1);
}
