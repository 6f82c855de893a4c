/* SPDX-License-Identifier: MIT */
#define _DEFAULT_SOURCE
#include "sbr_port_socketcan.h"

#include <errno.h>
#include <fcntl.h>
#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

sbr_status_t sbr_port_socketcan_open(sbr_port_socketcan_t *p, const char *ifname, int *os_error)
{
    struct sockaddr_can addr;
    struct ifreq ifr;
    int fd;
    int flags;

    if ((p == NULL) || (ifname == NULL)) {
        return SBR_ERR_NULL;
    }
    memset(p, 0, sizeof *p);
    p->fd = -1;
    p->retries = 3u;
    p->retry_wait_ms = 1u;
    if (os_error != NULL) {
        *os_error = 0;
    }
    fd = socket(PF_CAN, SOCK_RAW, CAN_RAW);
    if (fd < 0) {
        if (os_error != NULL) {
            *os_error = errno;
        }
        return SBR_ERR_STATE;
    }
    memset(&ifr, 0, sizeof ifr);
    strncpy(ifr.ifr_name, ifname, IFNAMSIZ - 1);
    if (ioctl(fd, SIOCGIFINDEX, &ifr) < 0) {
        if (os_error != NULL) {
            *os_error = errno;
        }
        close(fd);
        return SBR_ERR_STATE;
    }
    memset(&addr, 0, sizeof addr);
    addr.can_family = AF_CAN;
    addr.can_ifindex = ifr.ifr_ifindex;
    flags = fcntl(fd, F_GETFL, 0);
    if ((flags < 0) || (fcntl(fd, F_SETFL, flags | O_NONBLOCK) < 0) ||
        (bind(fd, (struct sockaddr *)&addr, sizeof addr) < 0)) {
        if (os_error != NULL) {
            *os_error = errno;
        }
        close(fd);
        return SBR_ERR_STATE;
    }
    p->fd = fd;
    return SBR_OK;
}

static sbr_status_t socketcan_send(void *ctx, const sbr_can_frame_t *frame)
{
    sbr_port_socketcan_t *p = (sbr_port_socketcan_t *)ctx;
    struct can_frame cf;
    uint32_t attempt;

    if ((p == NULL) || (frame == NULL)) {
        return SBR_ERR_NULL;
    }
    if ((p->fd < 0) || (frame->dlc > 8u) || (frame->id > CAN_SFF_MASK)) {
        return (p->fd < 0) ? SBR_ERR_STATE : SBR_ERR_RANGE;
    }
    memset(&cf, 0, sizeof cf);
    cf.can_id = frame->id;
    cf.can_dlc = frame->dlc;
    memcpy(cf.data, frame->data, frame->dlc);
    for (attempt = 0u; attempt <= p->retries; attempt++) {
        const ssize_t n = write(p->fd, &cf, sizeof cf);
        if (n == (ssize_t)sizeof cf) {
            p->sent++;
            return SBR_OK;
        }
        if ((n < 0) && ((errno == EAGAIN) || (errno == EWOULDBLOCK))) {
            p->busy++;
        } else if ((n < 0) && (errno == ENOBUFS)) {
            p->nobufs++;
        } else {
            return SBR_ERR_STATE;
        }
        if (attempt < p->retries) {
            struct pollfd pfd;
            pfd.fd = p->fd;
            pfd.events = POLLOUT;
            pfd.revents = 0;
            (void)poll(&pfd, 1, (int)p->retry_wait_ms);
        }
    }
    p->dropped++;
    return SBR_ERR_CAPACITY;
}

const sbr_can_port_t sbr_port_socketcan = {"socketcan", socketcan_send};

sbr_status_t sbr_port_socketcan_recv(sbr_port_socketcan_t *p, sbr_can_frame_t *frame,
                                     uint32_t wait_ms)
{
    struct can_frame cf;
    struct pollfd pfd;
    ssize_t n;
    if ((p == NULL) || (frame == NULL)) {
        return SBR_ERR_NULL;
    }
    if (p->fd < 0) {
        return SBR_ERR_STATE;
    }
    pfd.fd = p->fd;
    pfd.events = POLLIN;
    pfd.revents = 0;
    if (poll(&pfd, 1, (int)wait_ms) <= 0) {
        return SBR_ERR_CAPACITY;
    }
    n = read(p->fd, &cf, sizeof cf);
    if (n != (ssize_t)sizeof cf) {
        return ((n < 0) && ((errno == EAGAIN) || (errno == EWOULDBLOCK))) ? SBR_ERR_CAPACITY
                                                                          : SBR_ERR_STATE;
    }
    frame->id = cf.can_id & CAN_SFF_MASK;
    frame->dlc = cf.can_dlc;
    memset(frame->data, 0, sizeof frame->data);
    memcpy(frame->data, cf.data, cf.can_dlc > 8u ? 8u : cf.can_dlc);
    return SBR_OK;
}

void sbr_port_socketcan_close(sbr_port_socketcan_t *p)
{
    if ((p != NULL) && (p->fd >= 0)) {
        close(p->fd);
        p->fd = -1;
    }
}
