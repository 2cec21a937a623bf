/* SPDX-License-Identifier: MIT */
/*
 * fuzz.h: what the fuzz harnesses (tests/fuzz/fuzz_*.c) share. Each harness is one LLVMFuzzerTestOneInput that
 * writes its input to files in a private temporary directory and calls a public loader by path, as the programs
 * do: the loaders take paths, and the dispatcher looks at the extension (.nrrd, .nhdr, .nii, .nii.gz, .den).
 *
 * The same harness builds two ways: with clang and -fsanitize=fuzzer for `make fuzz` (libFuzzer's main), and with
 * the normal compiler and tests/fuzz/replay.c's main for `make test`, which replays tests/fuzz/seeds/ and
 * tests/fuzz/regress/ through every harness (tests/fuzz/replay.sh).
 *
 * Every input must leave the process as it found it: no file, allocation or descriptor survives a call, so a
 * finding replays the same on its own. Header-only, every function static inline.
 */
#ifndef VFP_FUZZ_H
#define VFP_FUZZ_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "io/volume.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define FZ_MAX_FILES 8

/* The directory, made on first use and removed at exit with the files written into it. */
static char fz_dir[64];
static char fz_files[FZ_MAX_FILES][128];
static int fz_nfiles;

static inline void fz_cleanup(void)
{
    for (int i = 0; i < fz_nfiles; i++)
        unlink(fz_files[i]);
    if (fz_dir[0])
        rmdir(fz_dir);
}

/* The path of `name` in the directory (a static buffer per name, so paths stay valid between calls). */
static inline const char *fz_path(const char *name)
{
    if (!fz_dir[0]) {
        const char *tmp = getenv("TMPDIR");
        snprintf(fz_dir, sizeof fz_dir, "%s/volfix-fuzz-XXXXXX", tmp && *tmp && strlen(tmp) < 32 ? tmp : "/tmp");
        if (!mkdtemp(fz_dir)) {
            perror("mkdtemp");
            abort();
        }
        atexit(fz_cleanup);
    }
    char path[128];
    snprintf(path, sizeof path, "%s/%s", fz_dir, name);
    for (int i = 0; i < fz_nfiles; i++)
        if (strcmp(fz_files[i], path) == 0)
            return fz_files[i];
    if (fz_nfiles == FZ_MAX_FILES)
        abort(); /* a harness names a handful of files */
    snprintf(fz_files[fz_nfiles], sizeof fz_files[0], "%s", path);
    return fz_files[fz_nfiles++];
}

/* With VOLFIX_SHOW_ERRORS=1 (as the unit tests take it), each input's outcome on stderr: "# loaded" or its error. */
static inline void fz_show(const char *err)
{
    if (getenv("VOLFIX_SHOW_ERRORS"))
        fprintf(stderr, "# %s\n", err ? err : "loaded");
}

/* Every error is one printable line: a file's bytes quoted in a message must not bring a line break, a tab or a
 * terminal escape with them. */
static inline void fz_check_line(const char *err)
{
    if (!err[0])
        abort();
    for (const unsigned char *c = (const unsigned char *)err; *c; c++)
        if (*c < 0x20 || *c == 0x7f)
            abort();
}

/* An error of a line-oriented parser (transfer functions, boards, scripts): "FILE:LINE: ..." or "FILE: ...". */
static inline void fz_check_error(const char *err, const char *path)
{
    size_t n = strlen(path);
    fz_show(err);
    fz_check_line(err);
    if (strncmp(err, path, n) != 0 || err[n] != ':')
        abort();
}

/* A line-oriented parser's outcome: 0 when it took the input, 1 when it refused it, after checking its error as
 * fz_check_error does. */
static inline int fz_refused(vfp_status_t status, const char *err, const char *path)
{
    if (status == VFP_OK) {
        fz_show(NULL);
        return 0;
    }
    fz_check_error(err, path);
    return 1;
}

/* Called first by every harness: removes the files the previous input wrote, so that no input sees another's
 * (a NRRD header may name any file in the directory as its data). */
static inline void fz_begin(void)
{
    for (int i = 0; i < fz_nfiles; i++)
        unlink(fz_files[i]);
}

/* Writes `size` bytes to the file `name` (replacing what an earlier input left there); returns its path. */
static inline const char *fz_write(const char *name, const void *data, size_t size)
{
    const char *path = fz_path(name);
    FILE *f = fopen(path, "wb");
    if (!f || (size && fwrite(data, 1, size, f) != size) || fclose(f) != 0) {
        perror(path);
        abort();
    }
    return path;
}

/* Loads a volume file as the programs do, and uses it as they do: the default window reads every voxel. An error
 * must be one non-empty line (it names the header, or the data file the header names), with nothing left
 * allocated. */
static inline void fz_load_volume(const char *path, const vfp_load_opts_t *opts)
{
    vfp_volume_t vol;
    char err[VFP_ERR_LEN];
    if (vfp_volume_load(&vol, path, opts, err, sizeof err) == VFP_OK) {
        fz_show(NULL);
        vf_window_t w = vfp_default_window(&vol);
        if (!(w.lo < w.hi) || !vol.data || vol.core.voxels != vol.data)
            abort();
        vfp_volume_free(&vol);
        return;
    }
    fz_show(err);
    fz_check_line(err);
    if (vol.data)
        abort();
}

#endif /* VFP_FUZZ_H */
