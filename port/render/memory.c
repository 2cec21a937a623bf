/* SPDX-License-Identifier: MIT */
/* memory.c: what rendering a volume needs, and what the machine has (see memory.h). */
#include "memory.h"

#include <stdio.h>
#include <string.h>
#include <sys/resource.h>

#define MB (1024.0 * 1024.0)

/* A "Key:   N kB" line of a /proc file, in bytes; 0 when the file or the key is not there. */
static uint64_t proc_kb(const char *path, const char *key)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return 0;
    char line[256];
    size_t n = strlen(key);
    unsigned long long kb = 0;
    while (fgets(line, sizeof line, f))
        if (strncmp(line, key, n) == 0 && line[n] == ':') {
            if (sscanf(line + n + 1, "%llu", &kb) != 1)
                kb = 0;
            break;
        }
    fclose(f);
    return (uint64_t)kb * 1024u;
}

uint64_t vfp_memory_available(void)
{
    uint64_t avail = proc_kb("/proc/meminfo", "MemAvailable");
    if (avail == 0)
        avail = UINT64_MAX;
    struct rlimit rl;
    if (getrlimit(RLIMIT_AS, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY) {
        uint64_t mapped = proc_kb("/proc/self/status", "VmSize");
        uint64_t left = (uint64_t)rl.rlim_cur > mapped ? (uint64_t)rl.rlim_cur - mapped : 0;
        avail = left < avail ? left : avail;
    }
    return avail;
}

uint64_t vfp_memory_renderer(const vf_params_t *params, const uint32_t dims[3], vf_voxel_t type)
{
    static const uint8_t unread = 0; /* vf_renderer_bytes wants voxels, but does not read them */
    vf_volume_t vol = {.dims = {dims[0], dims[1], dims[2]}, .spacing_q16 = {65536, 65536, 65536}, .type = type,
                       .voxels = &unread};
    size_t fixed;
    if (vf_renderer_bytes(params, &vol, &fixed) != VF_OK)
        return 0;
    return (uint64_t)fixed + fixed / 4; /* render_mt.c reserves a quarter more for the run lists */
}

vfp_status_t vfp_memory_check(const char *name, const uint32_t dims[3], uint64_t need, char *err, size_t errlen)
{
    uint64_t avail = vfp_memory_available();
    if (need <= avail)
        return VFP_OK;
    snprintf(err, errlen, "%s: %ux%ux%u needs %.0f MB (%.0f available)", name, dims[0], dims[1], dims[2],
             need / MB + 0.5, avail / MB);
    return VFP_ERR;
}
