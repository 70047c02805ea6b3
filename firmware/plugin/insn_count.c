/*
 * insn_count: a QEMU TCG plugin that counts the guest instructions executed
 * between two addresses, for fixshade's firmware (firmware/qemu).
 *
 *   qemu-system-arm ... -plugin ./libinsn_count.so,begin=0xADDR,end=0xADDR,out=FILE
 *
 * `begin` and `end` are the entry points of the firmware's marker functions
 * `fw_count_begin` and `fw_count_end` (from the ELF symbol table; the Thumb
 * bit is ignored). Every instruction adds one to a counter (an inline add,
 * exact, no callback per instruction); when the instruction at `begin`
 * executes the counter is noted, and when the one at `end` executes the
 * difference is appended to FILE as one line: the instructions executed
 * inside the counted region, callees included. The two marker functions'
 * own instructions and the calls to them are included: 4 to 6 instructions
 * per region, negligible.
 *
 * Optional `profile=FILE,region=N`: also count, per instruction address,
 * the executions inside the N-th counted region (0-based), and write
 * "address count" lines to FILE at exit (slower: one callback per
 * instruction). Used to see where a frame's instructions go.
 *
 * QEMU's plugin header (qemu-plugin.h) is not packaged by Debian 12, so the
 * few declarations used are written below from the documented plugin API
 * of QEMU 7.2 (API version 1); nothing else of QEMU is used.
 */
#include <inttypes.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- the documented QEMU plugin API, the parts this plugin uses ---- */
#define QEMU_PLUGIN_EXPORT __attribute__((visibility("default")))
typedef uint64_t qemu_plugin_id_t;
typedef struct qemu_info_t qemu_info_t; /* not read */
struct qemu_plugin_tb;
struct qemu_plugin_insn;
enum qemu_plugin_cb_flags {
    QEMU_PLUGIN_CB_NO_REGS,
    QEMU_PLUGIN_CB_R_REGS,
    QEMU_PLUGIN_CB_RW_REGS,
};
enum qemu_plugin_op {
    QEMU_PLUGIN_INLINE_ADD_U64,
};
typedef void (*qemu_plugin_vcpu_tb_trans_cb_t)(qemu_plugin_id_t id, struct qemu_plugin_tb *tb);
typedef void (*qemu_plugin_vcpu_udata_cb_t)(unsigned int vcpu_index, void *userdata);
typedef void (*qemu_plugin_udata_cb_t)(qemu_plugin_id_t id, void *userdata);
void qemu_plugin_register_vcpu_tb_trans_cb(qemu_plugin_id_t id, qemu_plugin_vcpu_tb_trans_cb_t cb);
void qemu_plugin_register_vcpu_insn_exec_cb(struct qemu_plugin_insn *insn,
                                            qemu_plugin_vcpu_udata_cb_t cb,
                                            enum qemu_plugin_cb_flags flags, void *userdata);
void qemu_plugin_register_vcpu_insn_exec_inline(struct qemu_plugin_insn *insn,
                                                enum qemu_plugin_op op, void *ptr, uint64_t imm);
size_t qemu_plugin_tb_n_insns(const struct qemu_plugin_tb *tb);
struct qemu_plugin_insn *qemu_plugin_tb_get_insn(const struct qemu_plugin_tb *tb, size_t idx);
uint64_t qemu_plugin_insn_vaddr(const struct qemu_plugin_insn *insn);
void qemu_plugin_register_atexit_cb(qemu_plugin_id_t id, qemu_plugin_udata_cb_t cb, void *userdata);
void qemu_plugin_outs(const char *string);
/* ---- end of the API declarations ---- */

QEMU_PLUGIN_EXPORT int qemu_plugin_version = 1;

static uint64_t executed;     /* every instruction, inline add */
static uint64_t at_begin;     /* `executed` when `begin` last ran */
static bool counting;
static uint64_t begin_addr, end_addr;
static FILE *out;
static unsigned regions;

/* Profile: one cell per translated instruction (an address translated
 * twice has two cells; the lines are summed by address afterwards). */
struct cell {
    uint64_t pc;
    uint64_t count;
    struct cell *next;
};
static struct cell *cells;
static const char *profile_path;
static uint64_t profile_region;

static void on_insn(unsigned int vcpu, void *udata)
{
    (void)vcpu;
    if (counting && regions == profile_region) {
        ((struct cell *)udata)->count++;
    }
}

static void on_begin(unsigned int vcpu, void *udata)
{
    (void)vcpu;
    (void)udata;
    at_begin = executed;
    counting = true;
}

static void on_end(unsigned int vcpu, void *udata)
{
    (void)vcpu;
    (void)udata;
    if (!counting) {
        return;
    }
    counting = false;
    fprintf(out, "%" PRIu64 "\n", executed - at_begin);
    fflush(out);
    regions++;
}

static void on_translate(qemu_plugin_id_t id, struct qemu_plugin_tb *tb)
{
    (void)id;
    size_t n = qemu_plugin_tb_n_insns(tb);
    for (size_t i = 0; i < n; i++) {
        struct qemu_plugin_insn *insn = qemu_plugin_tb_get_insn(tb, i);
        uint64_t pc = qemu_plugin_insn_vaddr(insn) & ~(uint64_t)1;
        qemu_plugin_register_vcpu_insn_exec_inline(insn, QEMU_PLUGIN_INLINE_ADD_U64, &executed, 1);
        if (profile_path) {
            struct cell *c = calloc(1, sizeof *c);
            if (!c) {
                abort();
            }
            c->pc = pc;
            c->next = cells;
            cells = c;
            qemu_plugin_register_vcpu_insn_exec_cb(insn, on_insn, QEMU_PLUGIN_CB_NO_REGS, c);
        }
        if (pc == begin_addr) {
            qemu_plugin_register_vcpu_insn_exec_cb(insn, on_begin, QEMU_PLUGIN_CB_NO_REGS, NULL);
        } else if (pc == end_addr) {
            qemu_plugin_register_vcpu_insn_exec_cb(insn, on_end, QEMU_PLUGIN_CB_NO_REGS, NULL);
        }
    }
}

static void on_exit_cb(qemu_plugin_id_t id, void *udata)
{
    (void)id;
    (void)udata;
    char line[96];
    snprintf(line, sizeof line, "insn_count: %u regions, %" PRIu64 " instructions in all\n",
             regions, executed);
    qemu_plugin_outs(line);
    if (out != stdout) {
        fclose(out);
    }
    if (profile_path) {
        FILE *f = fopen(profile_path, "w");
        if (f) {
            for (struct cell *c = cells; c; c = c->next) {
                if (c->count) {
                    fprintf(f, "0x%" PRIx64 " %" PRIu64 "\n", c->pc, c->count);
                }
            }
            fclose(f);
        }
    }
}

static bool parse_addr(const char *arg, const char *key, uint64_t *v)
{
    size_t k = strlen(key);
    if (strncmp(arg, key, k) != 0 || arg[k] != '=') {
        return false;
    }
    *v = strtoull(arg + k + 1, NULL, 0) & ~(uint64_t)1;
    return true;
}

QEMU_PLUGIN_EXPORT int qemu_plugin_install(qemu_plugin_id_t id, const qemu_info_t *info,
                                           int argc, char **argv)
{
    (void)info;
    const char *path = NULL;
    bool have_begin = false, have_end = false;
    for (int i = 0; i < argc; i++) {
        if (parse_addr(argv[i], "begin", &begin_addr)) {
            have_begin = true;
        } else if (parse_addr(argv[i], "end", &end_addr)) {
            have_end = true;
        } else if (strncmp(argv[i], "region=", 7) == 0) {
            profile_region = strtoull(argv[i] + 7, NULL, 0);
        } else if (strncmp(argv[i], "profile=", 8) == 0) {
            profile_path = argv[i] + 8;
        } else if (strncmp(argv[i], "out=", 4) == 0) {
            path = argv[i] + 4;
        } else {
            fprintf(stderr, "insn_count: unknown argument %s\n", argv[i]);
            return -1;
        }
    }
    if (!have_begin || !have_end) {
        fprintf(stderr, "insn_count: needs begin=ADDR,end=ADDR[,out=FILE]\n");
        return -1;
    }
    out = path ? fopen(path, "w") : stdout;
    if (!out) {
        perror(path);
        return -1;
    }
    qemu_plugin_register_vcpu_tb_trans_cb(id, on_translate);
    qemu_plugin_register_atexit_cb(id, on_exit_cb, NULL);
    return 0;
}
