/*
 * Tests of m0_timing.h against hand-assembled ARMv6-M encodings.
 * Build and run: gcc -O2 -Wall -Wextra -o t m0_timing_test.c && ./t
 */
#include <stdio.h>

#include "m0_timing.h"

static int check(unsigned h, unsigned h2, size_t reported, size_t size,
                 unsigned cycles, bool cond, const char *what)
{
    uint8_t p[4] = {h & 0xff, h >> 8, h2 & 0xff, h2 >> 8};
    bool c;
    size_t sz = thumb_size(p, reported);
    unsigned got = m0_cycles(p, sz, &c);
    if (sz != size || got != cycles || c != cond) {
        printf("FAIL %-28s %04x %04x: size %zu cycles %u cond %d, want %zu %u %d\n",
               what, h, h2, sz, got, c, size, cycles, cond);
        return 1;
    }
    return 0;
}

int main(void)
{
    int e = 0;
    e += check(0xb5f0, 0, 2, 2, 6, false, "push {r4-r7, lr}");
    e += check(0xb4f0, 0, 2, 2, 5, false, "push {r4-r7}");
    e += check(0xbdf0, 0, 2, 2, 8, false, "pop {r4-r7, pc}");
    e += check(0xbc03, 0, 2, 2, 3, false, "pop {r0, r1}");
    e += check(0x6808, 0, 2, 2, 2, false, "ldr r0, [r1]");
    e += check(0x6808, 0x1234, 4, 2, 2, false, "ldr r0, [r1] reported as 4");
    e += check(0x4801, 0, 2, 2, 2, false, "ldr r0, [pc, #4]");
    e += check(0x9001, 0, 2, 2, 2, false, "str r0, [sp, #4]");
    e += check(0x5c08, 0, 2, 2, 2, false, "ldrb r0, [r1, r0]");
    e += check(0xf000, 0xf800, 4, 4, 4, false, "bl");
    e += check(0x4770, 0, 2, 2, 3, false, "bx lr");
    e += check(0x4788, 0, 2, 2, 3, false, "blx r1");
    e += check(0x4687, 0, 2, 2, 3, false, "mov pc, r0");
    e += check(0x44ff, 0, 2, 2, 3, false, "add pc, pc");
    e += check(0x4478, 0, 2, 2, 1, false, "add r0, pc");
    e += check(0x46c0, 0, 2, 2, 1, false, "mov r8, r8");
    e += check(0x4540, 0, 2, 2, 1, false, "cmp r0, r8");
    e += check(0x4348, 0, 2, 2, 1, false, "muls r0, r1");
    e += check(0x1840, 0, 2, 2, 1, false, "adds r0, r0, r1");
    e += check(0x0040, 0, 2, 2, 1, false, "lsls r0, r0, #1");
    e += check(0xd0fe, 0, 2, 2, 1, true, "beq");
    e += check(0xdbfe, 0, 2, 2, 1, true, "blt");
    e += check(0xe7fe, 0, 2, 2, 3, false, "b");
    e += check(0xc806, 0, 2, 2, 3, false, "ldm r0!, {r1, r2}");
    e += check(0xc00e, 0, 2, 2, 4, false, "stm r0!, {r1-r3}");
    e += check(0xb002, 0, 2, 2, 1, false, "add sp, #8");
    e += check(0xa001, 0, 2, 2, 1, false, "adr r0, #4");
    e += check(0xb280, 0, 2, 2, 1, false, "uxth r0, r0");
    e += check(0xba00, 0, 2, 2, 1, false, "rev r0, r0");
    e += check(0xdf00, 0, 2, 2, 1, false, "svc 0");
    e += check(0xbf00, 0, 2, 2, 1, false, "nop");
    e += check(0xf3ef, 0x8008, 4, 4, 4, false, "mrs r0, msp");
    e += check(0xf3bf, 0x8f5f, 4, 4, 4, false, "dmb");
    e += check(0xbf08, 0, 2, 2, 0, false, "it eq (not ARMv6-M)");
    e += check(0xe8bd, 0x8ff0, 4, 4, 0, false, "pop.w (not ARMv6-M)");
    if (e) {
        printf("%d failures\n", e);
        return 1;
    }
    printf("m0_timing: all cases pass\n");
    return 0;
}
