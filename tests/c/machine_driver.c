/* Replays a machine input script against the generated C tr24 machines and
 * prints every input with its outputs, in the format of the Python simulator's
 * trace (tests/sim). Arguments: data_length timeout retry_limit slave_id...
 * Input lines: "<time> <machine> <kind> [<hex>]", machine m<id> (the master's
 * machine for slave <id>) or s<id> (slave <id>), kind send|receive|tick; a send
 * carries the receiver byte then the data. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "tr24.h"

#define MASTER_ID 1u
#define MAX_SLAVES 4

static tr24_master_t masters[MAX_SLAVES];
static tr24_slave_t slaves[MAX_SLAVES];
static unsigned slave_ids[MAX_SLAVES];
static int n_slaves;

/* the simulator's application: each byte plus the slave's ID */
static void reply_for(void *ctx, const uint8_t *command, uint8_t len, uint8_t *result)
{
    unsigned id = *(const unsigned *)ctx;
    for (uint8_t i = 0; i < len; i++) result[i] = (uint8_t)(command[i] + id);
}

static void hex(const char *label, const uint8_t *b, size_t n)
{
    printf("  %s ", label);
    for (size_t i = 0; i < n; i++) printf("%02x", b[i]);
    printf("\n");
}

static size_t unhex(const char *s, uint8_t *b, size_t cap)
{
    size_t n = 0;
    while (s[0] && s[1] && n < cap) {
        unsigned v;
        if (sscanf(s, "%2x", &v) != 1) break;
        b[n++] = (uint8_t)v;
        s += 2;
    }
    return n;
}

static int find(unsigned id)
{
    for (int i = 0; i < n_slaves; i++) if (slave_ids[i] == id) return i;
    return -1;
}

int main(int argc, char **argv)
{
    if (argc < 5) {
        fprintf(stderr, "usage: %s data_length timeout retry_limit slave_id...\n", argv[0]);
        return 2;
    }
    uint8_t data_length = (uint8_t)atoi(argv[1]);
    uint32_t timeout = (uint32_t)strtoul(argv[2], NULL, 10);
    uint8_t retry_limit = (uint8_t)atoi(argv[3]);
    for (int i = 4; i < argc && n_slaves < MAX_SLAVES; i++) {
        slave_ids[n_slaves] = (unsigned)atoi(argv[i]);
        if (tr24_master_init(&masters[n_slaves], data_length, timeout, retry_limit, MASTER_ID) != 0 ||
            tr24_slave_init(&slaves[n_slaves], data_length, (uint8_t)slave_ids[n_slaves], reply_for,
                            &slave_ids[n_slaves]) != 0) {
            fprintf(stderr, "bad parameters\n");
            return 2;
        }
        n_slaves++;
    }
    char line[512], who[16], kind[16], data[300];
    uint8_t bytes[TR24_MACHINE_MAX_PACKET + 1];
    tr24_machine_out_t out;
    while (fgets(line, sizeof line, stdin)) {
        unsigned long now;
        data[0] = '\0';
        if (sscanf(line, "%lu %15s %15s %299s", &now, who, kind, data) < 3) continue;
        int i = find((unsigned)atoi(who + 1));
        if (i < 0) {
            fprintf(stderr, "unknown machine %s\n", who);
            return 2;
        }
        size_t n = unhex(data, bytes, sizeof bytes);
        int rc;
        if (who[0] == 'm' && strcmp(kind, "send") == 0)
            rc = tr24_master_send(&masters[i], (uint32_t)now, bytes[0], bytes + 1, n - 1, &out);
        else if (who[0] == 'm' && strcmp(kind, "receive") == 0)
            rc = tr24_master_receive(&masters[i], (uint32_t)now, bytes, n, &out);
        else if (who[0] == 'm' && strcmp(kind, "tick") == 0)
            rc = tr24_master_tick(&masters[i], (uint32_t)now, &out);
        else if (who[0] == 's' && strcmp(kind, "receive") == 0)
            rc = tr24_slave_receive(&slaves[i], (uint32_t)now, bytes, n, &out);
        else {
            fprintf(stderr, "unknown input %s %s\n", who, kind);
            return 2;
        }
        printf("%lu %s %s%s%s\n", now, who, kind, data[0] ? " " : "", data);
        if (rc != 0) printf("  refused\n");
        if (out.sent_len) hex("sent", out.sent, out.sent_len);
        if (out.delivered_len) hex("delivered", out.delivered, out.delivered_len);
        if (out.executed_len) hex("executed", out.executed, out.executed_len);
        if (out.failed) printf("  failed %s\n", out.failed);
        if (out.dropped) hex("dropped", bytes, n);
    }
    return 0;
}
