/* SPDX-License-Identifier: MIT */
/**
 * @file part_model.h
 * @brief The recogniser's part model (thesis paper D): a library of prototype parts.
 *
 * A prototype is a part that recurs across training instances of signs: its descriptor,
 * the map and polarity it is found on, the offset from the part's centroid to the sign's
 * centre and the sign's width and height, all in units of the part's scale
 * (sbr_fd_t::scale), and the classes whose signs contain it (a ring is shared by every
 * prohibitory sign, a "5" only by some speed limits). Its vote weight is its precision on
 * training backgrounds. Per class, the cascade lists the class's prototypes, most reliable
 * first. Prototypes are grouped by map and polarity. The host tool sbr_train writes a
 * library as a const C table (lib/models/, sbr_model_gtsdb() in models.h) and as a file.
 */
#ifndef SBR_PART_MODEL_H
#define SBR_PART_MODEL_H

#include "sbr/fd.h"
#include "sbr/picto.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Largest number of sign classes of a model (sbr_model_t::class_count); a bound of the
    core, not of a dataset (GTSDB has 43). */
#define SBR_RECOG_MAX_CLASSES SBR_PICTO_MAX_CLASSES
/** Classes a prototype can be shared by. */
#define SBR_MODEL_PROTO_CLASSES 4u
/** "No class" in sbr_model_proto_t::class_id. */
#define SBR_MODEL_NO_CLASS 255u
/** Groups: map kind (0..3) x polarity (dark, bright). */
#define SBR_MODEL_GROUPS 8u
/** Model format version of the generated table and the file form (the class count and
    the classes' outlines are the model's). */
#define SBR_MODEL_VERSION 4u

/** One prototype part. */
typedef struct sbr_model_proto_s {
    float dx;        /**< sign centre x - part centroid x, in part scales */
    float dy;        /**< sign centre y - part centroid y, in part scales */
    float w;         /**< sign width in part scales, > 0 */
    float h;         /**< sign height in part scales, > 0 */
    float weight;    /**< vote weight (precision on training backgrounds), (0, 1] */
    uint16_t support; /**< training signs the part recurred in */
    uint8_t map;     /**< ::sbr_map_kind_t */
    uint8_t polarity; /**< ::SBR_MSER_DARK or ::SBR_MSER_BRIGHT */
    uint8_t class_id[SBR_MODEL_PROTO_CLASSES]; /**< classes, most frequent first;
                                                   ::SBR_MODEL_NO_CLASS pads */
    float class_p[SBR_MODEL_PROTO_CLASSES];     /**< share of each class, sum <= 1 */
} sbr_model_proto_t;

/** A prototype library. All arrays are borrowed (const tables or host memory). */
typedef struct sbr_model_s {
    uint32_t version;          /**< ::SBR_MODEL_VERSION */
    uint32_t fd_n;             /**< descriptor resampling size it was trained with */
    uint32_t fd_m;             /**< descriptor M */
    uint32_t proto_count;      /**< prototypes */
    /** Sign classes of the dataset the model was trained on, 1 .. ::SBR_RECOG_MAX_CLASSES;
        class ids are 0 .. class_count - 1 (GTSDB: 43). */
    uint32_t class_count;
    /** Outline of each class's sign (::sbr_picto_rim_t; ::SBR_PICTO_RIM_NONE: another or
        unknown outline), class_count entries used: the class stage's triangle view
        (sbr_recog_config_t::triangle_view) is for the classes with
        ::SBR_PICTO_RIM_TRIANGLE (GTSDB's danger signs). */
    uint8_t class_outline[SBR_RECOG_MAX_CLASSES];
    const sbr_fd_t *fds;       /**< proto_count descriptors, sorted by group */
    const sbr_model_proto_t *protos; /**< proto_count prototypes, same order */
    /** Group g = map * 2 + (polarity - 1) holds prototypes group_first[g] ..
        group_first[g + 1] - 1. */
    uint16_t group_first[SBR_MODEL_GROUPS + 1u];
    /** Class c's cascade is cascade[class_first[c] .. class_first[c + 1] - 1]
        (prototype indices, most reliable first). */
    uint16_t class_first[SBR_RECOG_MAX_CLASSES + 1u];
    const uint16_t *cascade;   /**< class_first[class_count] entries */
    float vote_error;          /**< vote threshold it was trained with */
    float score_threshold;     /**< operating point of part evidence alone (without a class
                                    stage), chosen on the training images */
} sbr_model_t;

/** Range of a model descriptor's scale (sbr_fd_t::scale, pixels of the training region),
    so that a region's scale over it stays a float32 value. */
#define SBR_MODEL_MIN_SCALE SBR_FD_TABLE_MIN_SCALE
#define SBR_MODEL_MAX_SCALE SBR_FD_TABLE_MAX_SCALE

/**
 * @brief Check a model: version, sizes, group and cascade indices, finite positive
 *        geometry, weights in (0, 1], class count in 1 .. ::SBR_RECOG_MAX_CLASSES and
 *        class ids below it, outlines in range, valid descriptors of unit energy with
 *        scales in ::SBR_MODEL_MIN_SCALE .. ::SBR_MODEL_MAX_SCALE. (The class stage is
 *        checked by sbr_picto_check(), and against the library by sbr_recog_init().)
 * @param[in] model the model
 * @return ::SBR_OK; ::SBR_ERR_NULL; ::SBR_ERR_CORRUPT for any inconsistency.
 */
sbr_status_t sbr_model_check(const sbr_model_t *model);

/**
 * @brief The prototype group of a part's map and polarity (sbr_model_t::group_first):
 *        map * 2 + (polarity - 1).
 * @param[in] map      the part's map (::sbr_map_kind_t)
 * @param[in] polarity ::SBR_MSER_DARK or ::SBR_MSER_BRIGHT
 * @return the group, 0 .. ::SBR_MODEL_GROUPS - 1; ::SBR_MODEL_GROUPS for a map or polarity
 *         out of range.
 */
uint32_t sbr_model_group(uint8_t map, uint8_t polarity);

#ifdef __cplusplus
}
#endif

#endif /* SBR_PART_MODEL_H */
