/* SPDX-License-Identifier: MIT */
/* The status names of include/sbr/status.h (sbr_status_str()). */
#include "sbr/status.h"

const char *sbr_status_str(sbr_status_t status)
{
    const char *s;

    switch (status) {
    case SBR_OK:
        s = "SBR_OK";
        break;
    case SBR_ERR_NULL:
        s = "SBR_ERR_NULL";
        break;
    case SBR_ERR_SIZE:
        s = "SBR_ERR_SIZE";
        break;
    case SBR_ERR_RANGE:
        s = "SBR_ERR_RANGE";
        break;
    case SBR_ERR_ALIGN:
        s = "SBR_ERR_ALIGN";
        break;
    case SBR_ERR_CAPACITY:
        s = "SBR_ERR_CAPACITY";
        break;
    case SBR_ERR_WORKSPACE:
        s = "SBR_ERR_WORKSPACE";
        break;
    case SBR_ERR_STATE:
        s = "SBR_ERR_STATE";
        break;
    case SBR_ERR_OVERLAP:
        s = "SBR_ERR_OVERLAP";
        break;
    case SBR_ERR_DEGENERATE:
        s = "SBR_ERR_DEGENERATE";
        break;
    case SBR_ERR_CORRUPT:
        s = "SBR_ERR_CORRUPT";
        break;
    default:
        s = "SBR_ERR_UNKNOWN";
        break;
    }
    return s;
}
