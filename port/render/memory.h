/* SPDX-License-Identifier: MIT */
/*
 * memory.h: what rendering a volume needs, told before it is allocated. A volume too large for the machine is
 * refused with one line, "FILE: 4096x4096x4096 needs 262144 MB (23543 available)", rather than left to the
 * operating system (an allocation that succeeds on paper and a process killed once the pages are touched).
 *
 * Available is the smaller of the kernel's MemAvailable (/proc/meminfo) and what the address-space limit
 * (RLIMIT_AS, ulimit -v) leaves beside what the process already maps; either may be unknown, and with neither
 * known nothing is refused.
 */
#ifndef VFP_MEMORY_H
#define VFP_MEMORY_H

#include <stddef.h>
#include <stdint.h>

#include "status.h"
#include "volfix.h"

/* Bytes the process can still allocate and use (UINT64_MAX when unknown). */
uint64_t vfp_memory_available(void);

/* The core renderer's bytes for these parameters and a volume of these dims and type, as vfp_render_open
 * allocates them (vf_renderer_bytes and the run lists' share on top), or 0 when the core refuses the volume (it
 * then says why itself). */
uint64_t vfp_memory_renderer(const vf_params_t *params, const uint32_t dims[3], vf_voxel_t type);

/* VFP_OK when `need` bytes fit in what is available; else VFP_ERR with "NAME: WxHxD needs N MB (M available)" in
 * err. */
vfp_status_t vfp_memory_check(const char *name, const uint32_t dims[3], uint64_t need, char *err, size_t errlen);

#endif /* VFP_MEMORY_H */
