/*
 * Decoding for insn_count.c: Thumb instruction size, and the Cortex-M0
 * cycle estimate of an ARMv6-M instruction from ARM DDI 0432C (Cortex-M0
 * Technical Reference Manual) table 3-1. Static functions, so that
 * m0_timing_test.c can test them without QEMU.
 */
#ifndef M0_TIMING_H
#define M0_TIMING_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

static unsigned popcount8(unsigned v)
{
    return (unsigned)__builtin_popcount(v & 0xff);
}

/*
 * Cortex-M0 cycles of one instruction, conditional branches as not taken.
 * Sets *cond for B<cond>. Returns 0 for an instruction outside ARMv6-M.
 */
static unsigned m0_cycles(const uint8_t *p, size_t size, bool *cond)
{
    *cond = false;
    uint16_t h = (uint16_t)(p[0] | (p[1] << 8));
    if (size == 4) {
        uint16_t h2 = (uint16_t)(p[2] | (p[3] << 8));
        if ((h & 0xf800) == 0xf000 && (h2 & 0xd000) == 0xd000) {
            return 4; /* BL */
        }
        if ((h & 0xffe0) == 0xf380 || (h & 0xffff) == 0xf3ef ||
            (h & 0xfff0) == 0xf3b0) {
            return 4; /* MSR, MRS, DSB/DMB/ISB */
        }
        return 0;
    }
    switch (h >> 12) {
    case 0x0: case 0x1: case 0x2: case 0x3:
        return 1; /* shifts, add/sub, mov/cmp/add/sub imm8 */
    case 0x4:
        if ((h & 0xfc00) == 0x4000) {
            return 1; /* data processing, MULS */
        }
        if ((h & 0xff00) == 0x4700) {
            return 3; /* BX, BLX */
        }
        if ((h & 0xfc00) == 0x4400) {
            unsigned op = (h >> 8) & 3;
            unsigned rd = (h & 7) | ((h >> 4) & 8);
            if (op != 1 && rd == 15) {
                return 3; /* ADD PC, Rm / MOV PC, Rm */
            }
            return 1;
        }
        return 2; /* LDR literal */
    case 0x5: case 0x6: case 0x7: case 0x8: case 0x9:
        return 2; /* loads and stores */
    case 0xa:
        return 1; /* ADR, ADD Rd, SP, #imm */
    case 0xb:
        if ((h & 0xfe00) == 0xb400) {
            return 1 + popcount8(h) + ((h >> 8) & 1); /* PUSH {.., LR} */
        }
        if ((h & 0xfe00) == 0xbc00) {
            return (h & 0x100) ? 4 + popcount8(h) : 1 + popcount8(h); /* POP */
        }
        if ((h & 0xff00) == 0xbf00) {
            return (h & 0xf) ? 0 : 1; /* hints (IT is not ARMv6-M) */
        }
        return 1; /* ADD/SUB SP, extend, REV, CPS, BKPT */
    case 0xc:
        return 1 + popcount8(h); /* LDM, STM */
    case 0xd:
        if ((h & 0x0f00) == 0x0f00) {
            return 1; /* SVC */
        }
        if ((h & 0x0f00) == 0x0e00) {
            return 0; /* UDF */
        }
        *cond = true;
        return 1; /* B<cond>, +2 when taken */
    case 0xe:
        if ((h & 0xf800) == 0xe000) {
            return 3; /* B */
        }
        return 0;
    default:
        return 0;
    }
}

/*
 * The size of a Thumb instruction from its first halfword. QEMU 7.2 can
 * report 4 bytes for a 16-bit instruction in the last halfword before a
 * 1 KiB page boundary (it reads ahead to check for a 32-bit one), so the
 * reported size is not trusted.
 */
static size_t thumb_size(const uint8_t *p, size_t reported)
{
    if (reported < 2) {
        return reported;
    }
    unsigned top5 = p[1] >> 3;
    return (top5 == 0x1d || top5 == 0x1e || top5 == 0x1f) ? 4 : 2;
}

#endif
