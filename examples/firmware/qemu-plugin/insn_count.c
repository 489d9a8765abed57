/*
 * insn_count: a QEMU TCG plugin that counts the guest instructions executed
 * inside regions marked by the firmware, exactly (one inline add per
 * executed instruction).
 *
 * Markers (Thumb hint instructions that rustc/LLVM never emit and QEMU
 * executes as no-ops):
 *   YIELD (0xbf10) toggles counting on/off; a region may be made of several
 *                  counted stretches (e.g. one per band of a frame);
 *   SEV   (0xbf40) closes the region: prints its totals and starts the next.
 * The markers themselves are not counted.
 *
 * With `prof=FILE` it also counts, per instruction address, the executions
 * inside counted stretches (only of the regions listed by `regions=A:B:..`
 * when given) and writes `ADDRESS COUNT` lines (both decimal) to FILE at exit: `../profile.sh` turns them into a per-function
 * table. A per-instruction callback makes this mode several times slower.
 *
 * Output (QEMU log, enable with `-d plugin`, redirect with `-D FILE`):
 *   region N: insns X est_m0_cycles Y
 * and at exit `total: regions N` (plus a warning line when something looked
 * wrong, e.g. a region closed while counting was on).
 *
 * With the plugin argument `m0=on` it also estimates Cortex-M0 cycles for
 * ARMv6-M code from ARM DDI 0432C (Cortex-M0 TRM) table 3-1: ALU and MULS 1
 * (single-cycle multiplier option), loads/stores 2, LDM/STM/PUSH/POP 1+N,
 * POP {..,PC} 4+N (N = registers besides PC), B<cond> 1 (not taken) or 3
 * (taken), B/BX/BLX/ADD PC/MOV PC 3, BL 4, MSR/MRS/DSB/DMB/ISB 4. It is an
 * ESTIMATE: zero wait states, no exception entry or exit, no bus
 * contention. Without `m0=on` est_m0_cycles is printed as "-". The decoder
 * is in m0_timing.h. A conditional branch ends a QEMU translation block, so
 * it was taken when the next block executed does not start right after it.
 *
 * Debian's QEMU (7.2, plugin API version 1) exports the qemu_plugin_* API
 * but ships no header: the few declarations used are written out here.
 * Build: gcc -O2 -shared -fPIC -o insn_count.so insn_count.c
 * Use:   qemu-system-arm ... -plugin ./insn_count.so,m0=on -d plugin -D log
 */
#include <inttypes.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "m0_timing.h"

/* ---- the part of qemu-plugin.h (API version 1) this plugin uses ---- */
typedef uint64_t qemu_plugin_id_t;
typedef struct qemu_info_t qemu_info_t; /* opaque here: not read */
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
typedef void (*qemu_plugin_vcpu_tb_trans_cb_t)(qemu_plugin_id_t id,
                                               struct qemu_plugin_tb *tb);
typedef void (*qemu_plugin_vcpu_udata_cb_t)(unsigned int vcpu_index,
                                            void *userdata);
typedef void (*qemu_plugin_udata_cb_t)(qemu_plugin_id_t id, void *userdata);

void qemu_plugin_register_vcpu_tb_trans_cb(qemu_plugin_id_t id,
                                           qemu_plugin_vcpu_tb_trans_cb_t cb);
size_t qemu_plugin_tb_n_insns(const struct qemu_plugin_tb *tb);
uint64_t qemu_plugin_tb_vaddr(const struct qemu_plugin_tb *tb);
struct qemu_plugin_insn *qemu_plugin_tb_get_insn(const struct qemu_plugin_tb *tb,
                                                 size_t idx);
const void *qemu_plugin_insn_data(const struct qemu_plugin_insn *insn);
size_t qemu_plugin_insn_size(const struct qemu_plugin_insn *insn);
uint64_t qemu_plugin_insn_vaddr(const struct qemu_plugin_insn *insn);
void qemu_plugin_register_vcpu_insn_exec_inline(struct qemu_plugin_insn *insn,
                                                enum qemu_plugin_op op,
                                                void *ptr, uint64_t imm);
void qemu_plugin_register_vcpu_insn_exec_cb(struct qemu_plugin_insn *insn,
                                            qemu_plugin_vcpu_udata_cb_t cb,
                                            enum qemu_plugin_cb_flags flags,
                                            void *userdata);
void qemu_plugin_register_vcpu_tb_exec_cb(struct qemu_plugin_tb *tb,
                                          qemu_plugin_vcpu_udata_cb_t cb,
                                          enum qemu_plugin_cb_flags flags,
                                          void *userdata);
void qemu_plugin_register_atexit_cb(qemu_plugin_id_t id,
                                    qemu_plugin_udata_cb_t cb, void *userdata);
void qemu_plugin_outs(const char *string);

__attribute__((visibility("default"))) int qemu_plugin_version = 1;

/* ---- state (single vCPU boards: no locking needed) ---- */

/* Running totals since start, snapshotted at the markers. */
static uint64_t all_insns;
static uint64_t all_cycles; /* M0 estimate, branches counted as not taken */

static bool counting;
static uint64_t start_insns, start_cycles;
static uint64_t region_insns, region_cycles, region_taken;
static unsigned region_no;
static unsigned warnings;
static uint64_t unknown_m0; /* instructions without an M0 timing */
static bool m0_mode;

/* Per-address profile (prof=FILE): counts indexed by address / 2. */
#define PROF_LIMIT (1u << 24) /* code addresses below 16 MiB */
static uint64_t *prof;
static const char *prof_path;
static uint64_t prof_regions; /* bit r: profile region r; 0 = all */
static bool prof_on;          /* counting, and in a profiled region */

/* Per translated block, for taken conditional branches. */
struct tb_info {
    uint64_t vaddr;
    bool ends_cond;       /* last instruction is a conditional branch */
    uint64_t fallthrough; /* address after it */
};
static const struct tb_info *prev_tb;
/* Whether the instructions executing now are counted; follows the markers
 * inside a block. */
static bool branch_counted;

static void outf(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
static void outf(const char *fmt, ...)
{
    char buf[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    qemu_plugin_outs(buf);
}

static void on_yield(unsigned int vcpu, void *ud)
{
    (void)vcpu;
    (void)ud;
    if (!counting) {
        start_insns = all_insns;
        start_cycles = all_cycles;
        counting = true;
    } else {
        region_insns += all_insns - start_insns;
        region_cycles += all_cycles - start_cycles;
        counting = false;
    }
    branch_counted = counting;
    prof_on = counting && (prof_regions == 0 ||
                           (region_no < 64 && (prof_regions >> region_no) & 1));
}

static void on_prof(unsigned int vcpu, void *ud)
{
    (void)vcpu;
    if (prof_on) {
        prof[(uintptr_t)ud >> 1]++;
    }
}

static void on_sev(unsigned int vcpu, void *ud)
{
    (void)vcpu;
    (void)ud;
    if (counting) {
        outf("insn_count: warning: region %u closed while counting\n",
             region_no);
        warnings++;
        on_yield(0, NULL);
    }
    if (m0_mode) {
        outf("region %u: insns %" PRIu64 " est_m0_cycles %" PRIu64 "\n",
             region_no, region_insns, region_cycles + 2 * region_taken);
    } else {
        outf("region %u: insns %" PRIu64 " est_m0_cycles -\n", region_no,
             region_insns);
    }
    region_no++;
    region_insns = region_cycles = region_taken = 0;
}

static void on_tb(unsigned int vcpu, void *ud)
{
    (void)vcpu;
    const struct tb_info *t = ud;
    if (prev_tb && prev_tb->ends_cond && branch_counted &&
        t->vaddr != prev_tb->fallthrough) {
        region_taken++;
    }
    prev_tb = t;
    branch_counted = counting;
}

static void on_tb_trans(qemu_plugin_id_t id, struct qemu_plugin_tb *tb)
{
    (void)id;
    size_t n = qemu_plugin_tb_n_insns(tb);
    struct tb_info *t = calloc(1, sizeof *t); /* lives as long as QEMU */
    if (!t) {
        abort();
    }
    t->vaddr = qemu_plugin_tb_vaddr(tb);
    if (m0_mode) {
        qemu_plugin_register_vcpu_tb_exec_cb(tb, on_tb, QEMU_PLUGIN_CB_NO_REGS,
                                             t);
    }
    for (size_t i = 0; i < n; i++) {
        struct qemu_plugin_insn *insn = qemu_plugin_tb_get_insn(tb, i);
        const uint8_t *p = qemu_plugin_insn_data(insn);
        size_t size = thumb_size(p, qemu_plugin_insn_size(insn));
        if (size == 2 && p[0] == 0x10 && p[1] == 0xbf) {
            qemu_plugin_register_vcpu_insn_exec_cb(insn, on_yield,
                                                   QEMU_PLUGIN_CB_NO_REGS, NULL);
            continue;
        }
        if (size == 2 && p[0] == 0x40 && p[1] == 0xbf) {
            qemu_plugin_register_vcpu_insn_exec_cb(insn, on_sev,
                                                   QEMU_PLUGIN_CB_NO_REGS, NULL);
            continue;
        }
        qemu_plugin_register_vcpu_insn_exec_inline(
            insn, QEMU_PLUGIN_INLINE_ADD_U64, &all_insns, 1);
        uint64_t va = qemu_plugin_insn_vaddr(insn);
        if (prof && va < PROF_LIMIT) {
            qemu_plugin_register_vcpu_insn_exec_cb(
                insn, on_prof, QEMU_PLUGIN_CB_NO_REGS, (void *)(uintptr_t)va);
        }
        if (m0_mode) {
            bool cond;
            unsigned c = m0_cycles(p, size, &cond);
            if (c == 0) {
                /* Not ARMv6-M: count 1 and report it at exit. */
                qemu_plugin_register_vcpu_insn_exec_inline(
                    insn, QEMU_PLUGIN_INLINE_ADD_U64, &unknown_m0, 1);
                c = 1;
            }
            qemu_plugin_register_vcpu_insn_exec_inline(
                insn, QEMU_PLUGIN_INLINE_ADD_U64, &all_cycles, c);
            if (cond && i + 1 == n) {
                t->ends_cond = true;
                t->fallthrough = qemu_plugin_insn_vaddr(insn) + size;
            } else if (cond) {
                /* QEMU ends a block at every branch; if not, say so. */
                outf("insn_count: warning: conditional branch inside a "
                     "block at 0x%" PRIx64 "\n",
                     qemu_plugin_insn_vaddr(insn));
                warnings++;
            }
        }
    }
}

static void on_plugin_exit(qemu_plugin_id_t id, void *ud)
{
    (void)id;
    (void)ud;
    if (counting) {
        outf("insn_count: warning: counting still on at exit\n");
        warnings++;
    }
    if (unknown_m0) {
        outf("insn_count: warning: %" PRIu64
             " executed instructions have no ARMv6-M timing (counted as 1)\n",
             unknown_m0);
        warnings++;
    }
    if (prof) {
        FILE *f = fopen(prof_path, "w");
        if (!f) {
            outf("insn_count: warning: cannot write %s\n", prof_path);
            warnings++;
        } else {
            for (uint64_t i = 0; i < PROF_LIMIT / 2; i++) {
                if (prof[i]) {
                    fprintf(f, "%" PRIu64 " %" PRIu64 "\n", 2 * i, prof[i]);
                }
            }
            fclose(f);
        }
    }
    outf("total: regions %u insns %" PRIu64 " warnings %u\n", region_no,
         all_insns, warnings);
}

__attribute__((visibility("default"))) int
qemu_plugin_install(qemu_plugin_id_t id, const qemu_info_t *info, int argc,
                    char **argv)
{
    (void)info;
    for (int i = 0; i < argc; i++) {
        if (!strcmp(argv[i], "m0=on") || !strcmp(argv[i], "m0=true")) {
            m0_mode = true;
        } else if (!strcmp(argv[i], "m0=off") || !strcmp(argv[i], "m0=false")) {
            m0_mode = false;
        } else if (!strncmp(argv[i], "prof=", 5) && argv[i][5]) {
            prof_path = argv[i] + 5;
        } else if (!strncmp(argv[i], "regions=", 8)) {
            for (char *p = argv[i] + 8; *p;) {
                char *end;
                unsigned long r = strtoul(p, &end, 10);
                if (end == p || r >= 64 || (*end && *end != ':')) {
                    fprintf(stderr, "insn_count: bad regions %s\n", argv[i]);
                    return -1;
                }
                prof_regions |= 1ull << r;
                p = *end ? end + 1 : end;
            }
        } else {
            fprintf(stderr, "insn_count: unknown argument %s\n", argv[i]);
            return -1;
        }
    }
    if (prof_path) {
        prof = calloc(PROF_LIMIT / 2, sizeof *prof);
        if (!prof) {
            fprintf(stderr, "insn_count: out of memory for prof\n");
            return -1;
        }
    }
    qemu_plugin_register_vcpu_tb_trans_cb(id, on_tb_trans);
    qemu_plugin_register_atexit_cb(id, on_plugin_exit, NULL);
    return 0;
}
