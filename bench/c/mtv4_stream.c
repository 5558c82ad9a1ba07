/* mtv4 stream parsing for host_bench, built by bench/c_host.py once for each CRC method
 * with -DMTV4_CRC_<METHOD> -DMETHOD=<method>, its functions named *_<method>, so the
 * methods run side by side in one process. Each returns the good frames it found in
 * the capture. */
#include <stddef.h>
#include "mtv4.h"

#define JOIN(name, method) name##_##method
#define NAMED(name, method) JOIN(name, method)
#define VARIANT(name) NAMED(name, METHOD)

long VARIANT(mtv4_feed)(const unsigned char *buf, size_t len);
long VARIANT(mtv4_scan)(const unsigned char *buf, size_t len);

/* One byte at a time: mtv4_parser_feed / mtv4_parser_next. */
long VARIANT(mtv4_feed)(const unsigned char *buf, size_t len)
{
    mtv4_parser_t p;
    mtv4_message_t m;
    long good = 0;
    size_t i;
    mtv4_parser_init(&p, MTV4_DIR_ANY);
    for (i = 0; i < len; i++) {
        int rc;
        mtv4_parser_feed(&p, buf[i]);
        while ((rc = mtv4_parser_next(&p, &m)) != 0) {
            good += rc == 1;
        }
    }
    return good;
}

/* In place: mtv4_scan over the whole capture. */
long VARIANT(mtv4_scan)(const unsigned char *buf, size_t len)
{
    mtv4_scan_state_t s;
    mtv4_message_t m;
    long good = 0;
    size_t pos = 0;
    mtv4_scan_start(&s, MTV4_DIR_ANY);
    for (;;) {
        size_t used;
        int rc = mtv4_scan(&s, buf + pos, len - pos, &used, &m);
        pos += used;
        if (rc == 0) {
            return good;
        }
        good += rc == 1;
    }
}
