/* SPDX-License-Identifier: MIT */
/* render_mt.c: the core renderer with malloc'd memory and pthreads (see render_mt.h). */
#include "render_mt.h"

#include <limits.h>
#include <linux/futex.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/syscall.h>
#include <time.h>
#include <unistd.h>

/* Compositing bands: at most BAND_MOST rows (a slab's set-up is paid once a band, so one thread takes bands this
 * tall), and with threads a share of the rows left, never fewer than BAND_FEWEST (next_band). Warp bands likewise,
 * in output rows. */
#define BAND_MOST 32
#define BAND_FEWEST 8
#define WARP_MOST 16
#define WARP_FEWEST 4
/* Parts of a stale table a thread: more than one, so that a thread that finishes its part early takes another */
#define PARTS_PER_THREAD 4
/* Slab ranges of each principal axis a thread when a transfer function's run lists are encoded in parts: with
 * three axes, six parts a thread, so that the last part taken costs the thread that is late a sixth of its share */
#define RANGES_PER_THREAD 2
/* How long a thread that waits for the others polls before it sleeps: longer than a frame's usual imbalance and
 * the main thread's work between frames (a few tens of microseconds), short enough not to hold a shared core. */
#define SPIN_NS 60000
/* A diagonal's state in the threads' copies of a table built as read (struct vfp_pool): 0 no copy has it,
 * BUILDING a thread is building it, READY | t thread t's copy has it */
#define BUILDING 0x100u
#define READY 0x200u

enum { FAIL_TABLES, FAIL_BANDS };

/* What the workers are woken for: a frame, or the parts of a transfer function's run-length encoding. */
enum { JOB_FRAME, JOB_ENCODE };

/* What one frame (or encoding) gives every thread: the stages run one after another, each shared out by a
 * counter. */
typedef struct frame_work {
    vfp_render_t *r;
    int job;
    uint32_t encode_parts;      /* JOB_ENCODE: the parts vf_renderer_set_tf_begin left, claimed with next_part */
    const vf_image_t *image;
    uint32_t table_parts;       /* parts of a stale table to build before compositing, 0 when it is up to date */
    uint32_t int_rows, out_rows; /* intermediate rows to composite, output rows to warp */
    int threads;                /* the threads working on it, the calling one included */
    _Alignas(64) atomic_uint next_part;
    atomic_uint next_row, next_warp;
    atomic_int status[2];       /* the first failure of the table's parts, and of the bands; VF_OK otherwise */
    double t_tables, t_composite; /* when the stages ended, on the calling thread's clock */
} frame_work_t;

typedef struct worker {
    struct vfp_pool *pool;
    int index;                  /* 1 .. workers; the calling thread is 0 */
} worker_t;

struct vfp_pool {
    pthread_t ids[VFP_MAX_THREADS];
    worker_t args[VFP_MAX_THREADS];
    int workers;
    frame_work_t work;
    /* each word a line of its own: the threads poll them while others write the counters */
    _Alignas(64) atomic_uint posted; /* frames posted so far; quit is set before the last post */
    atomic_int quit;
    _Alignas(64) atomic_uint arrived; /* threads at the barrier in this phase */
    _Alignas(64) atomic_uint phase;   /* barriers passed */
    _Alignas(64) atomic_int sleepers; /* threads asleep on a futex, or about to be */
    _Alignas(64) atomic_uint diagonal[VF_MAX_TABLE]; /* per diagonal: 0, BUILDING or READY | t */
};

static vfp_status_t create_core(vfp_render_t *r, size_t arena_bytes, char *err, size_t errlen);
static uint32_t table_parts(int threads);
static vfp_status_t apply(vfp_render_t *r, int window_changed, char *err, size_t errlen);
static struct vfp_pool *pool_start(int threads);
static void pool_stop(struct vfp_pool *pool);
static void *worker_main(void *arg);
static void run_frame(struct vfp_pool *pool, frame_work_t *work, int index);
static void run_encode(struct vfp_pool *pool, frame_work_t *work);
static vf_status_t set_tf_parts(vfp_render_t *r);
static bool fill_diagonal(void *context, uint32_t diagonal);
static void built_diagonal(void *context, uint32_t diagonal);
static void barrier(struct vfp_pool *pool);
static void wait_while(struct vfp_pool *pool, atomic_uint *word, unsigned value);
static void wake_all(struct vfp_pool *pool, atomic_uint *word);

double vfp_now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

vfp_status_t vfp_render_open(vfp_render_t *r, const vf_params_t *params, const vf_volume_t *volume, int threads,
                             char *err, size_t errlen)
{
    memset(r, 0, sizeof *r);
    r->params = *params;
    r->volume = volume;
    r->threads = threads < 1 ? 1 : threads > VFP_MAX_THREADS ? VFP_MAX_THREADS : threads;
    r->band_rows = BAND_MOST;
    size_t fixed;
    vf_status_t s = vf_renderer_bytes(params, volume, &fixed);
    if (s != VF_OK) {
        snprintf(err, errlen, "cannot render this volume: %s", vf_status_text(s));
        return VFP_ERR;
    }
    /* The run lists come on top; a quarter of the fixed part is usually plenty, and set_tf grows it if not. */
    if (create_core(r, fixed + fixed / 4, err, errlen))
        return VFP_ERR;
    if (r->threads > 1)
        r->pool = pool_start(r->threads); /* NULL if no worker would start: slower, not wrong */
    return VFP_OK;
}

vfp_status_t vfp_render_set_window(vfp_render_t *r, vf_window_t window, char *err, size_t errlen)
{
    r->window = window;
    r->have_window = 1;
    return apply(r, 1, err, errlen);
}

vfp_status_t vfp_render_set_tf(vfp_render_t *r, const vf_tf_point_t *points, uint32_t count, char *err, size_t errlen)
{
    if (count > VF_MAX_TF_POINTS) {
        snprintf(err, errlen, "transfer function has %u points (at most %d)", count, VF_MAX_TF_POINTS);
        return VFP_ERR;
    }
    memcpy(r->tf_points, points, sizeof *points * count);
    r->tf.points = r->tf_points;
    r->tf.count = count;
    r->have_tf = 1;
    return apply(r, 0, err, errlen);
}

/* One wake-up of the workers a frame: a stale table's parts, then the compositing bands, then the warp bands, with
 * a barrier between stages (each reads what the one before wrote). */
vfp_status_t vfp_render_frame(vfp_render_t *r, const vf_view_t *view, const vf_image_t *image, char *err, size_t errlen)
{
    double t0 = vfp_now_ms();
    /* on one thread the bands (one after another) build the diagonals of a stale table they read; with threads
     * each in its own copy of the table, or where the core cannot, the table is built first in parts */
    struct vfp_pool *pool = r->pool;
    const vf_frame_t frame = {.view = *view, .width = image->width, .height = image->height,
                              .table_parts = pool ? table_parts(r->threads) : 0, .one_thread = !pool,
                              .thread_tables = pool && r->table_copy_bytes};
    vf_status_t s = vf_renderer_begin(r->core, &frame);
    if (s != VF_OK) {
        snprintf(err, errlen, "cannot begin a frame: %s", vf_status_text(s));
        return VFP_ERR;
    }
    frame_work_t local, *work = pool ? &pool->work : &local;
    work->r = r;
    work->job = JOB_FRAME;
    work->image = image;
    work->table_parts = vf_renderer_table_parts(r->core);
    work->int_rows = vf_renderer_factor(r->core)->int_h;
    work->out_rows = image->height;
    work->threads = pool ? pool->workers + 1 : 1;
    atomic_init(&work->next_part, 0);
    atomic_init(&work->next_row, 0);
    atomic_init(&work->next_warp, 0);
    atomic_init(&work->status[FAIL_TABLES], VF_OK);
    atomic_init(&work->status[FAIL_BANDS], VF_OK);
    if (pool) {
        for (uint32_t d = 0; d < r->params.table_size && d < VF_MAX_TABLE; d++)
            atomic_store_explicit(&pool->diagonal[d], 0, memory_order_relaxed); /* none built in any copy */
        atomic_fetch_add(&pool->posted, 1); /* sequentially consistent: the work above is seen with it */
        wake_all(pool, &pool->posted);
    }
    run_frame(pool, work, 0);
    double t3 = vfp_now_ms();
    s = (vf_status_t)atomic_load(&work->status[FAIL_TABLES]);
    if (s != VF_OK) {
        snprintf(err, errlen, "cannot begin a frame: %s", vf_status_text(s));
        return VFP_ERR;
    }
    s = (vf_status_t)atomic_load(&work->status[FAIL_BANDS]);
    if (s != VF_OK) {
        snprintf(err, errlen, "cannot render a frame: %s", vf_status_text(s));
        return VFP_ERR;
    }
    r->ms_tables = work->t_tables - t0;
    r->ms_composite = work->t_composite - work->t_tables;
    r->ms_warp = t3 - work->t_composite;
    return VFP_OK;
}

void vfp_render_close(vfp_render_t *r)
{
    if (r->pool)
        pool_stop(r->pool);
    for (int t = 0; t < VFP_MAX_THREADS; t++) {
        free(r->scratch[t]);
        free(r->table_copy[t]);
    }
    free(r->arena_buf);
    memset(r, 0, sizeof *r);
}

static vfp_status_t create_core(vfp_render_t *r, size_t arena_bytes, char *err, size_t errlen)
{
    free(r->arena_buf); /* the core lived in it: gone with it, so that a failure below leaves nothing dangling */
    r->core = NULL;
    r->arena_buf = malloc(arena_bytes);
    if (!r->arena_buf) {
        snprintf(err, errlen, "out of memory: the renderer needs %zu MB", arena_bytes >> 20);
        return VFP_ERR;
    }
    vf_arena_init(&r->arena, r->arena_buf, arena_bytes);
    vf_status_t s = vf_renderer_create(&r->core, &r->params, r->volume, &r->arena);
    r->core_fresh = 1; /* it has neither window nor transfer function yet */
    if (s != VF_OK) {
        snprintf(err, errlen, "cannot create the renderer: %s", vf_status_text(s));
        return VFP_ERR;
    }
    /* Scratch for the tallest band or a table part, per thread; the core sizes it for any view of this volume. */
    r->scratch_bytes = vf_renderer_band_scratch_bytes(r->core, r->band_rows);
    if (r->threads > 1 && vf_renderer_table_part_bytes(r->core) > r->scratch_bytes)
        r->scratch_bytes = vf_renderer_table_part_bytes(r->core);
    for (int t = 0; t < r->threads; t++) {
        free(r->scratch[t]);
        r->scratch[t] = malloc(r->scratch_bytes);
        if (!r->scratch[t]) {
            snprintf(err, errlen, "out of memory for band scratch");
            return VFP_ERR;
        }
    }
    /* a copy of the table a thread, for frames that build it as read */
    r->table_copy_bytes = r->threads > 1 ? vf_renderer_thread_table_bytes(r->core) : 0;
    for (int t = 0; t < r->threads && r->table_copy_bytes; t++) {
        free(r->table_copy[t]);
        r->table_copy[t] = malloc(r->table_copy_bytes);
        if (!r->table_copy[t]) {
            snprintf(err, errlen, "out of memory for the threads' copies of the table (%zu KB each)",
                     r->table_copy_bytes >> 10);
            return VFP_ERR;
        }
    }
    return VFP_OK;
}

/* Give the core what changed (the window, or the transfer function), growing the arena once if the run lists
 * need it; a new core gets both. Each core call re-encodes the runs, so a transfer-function change must not
 * set the window again: that would rebuild the slices and encode twice, which a turning level knob would feel. */
static vfp_status_t apply(vfp_render_t *r, int window_changed, char *err, size_t errlen)
{
    double t0 = vfp_now_ms();
    for (int attempt = 0; attempt < 2; attempt++) {
        vf_status_t s = VF_OK;
        if (r->have_window && (window_changed || r->core_fresh))
            s = vf_renderer_set_window(r->core, r->window);
        if (s == VF_OK && r->have_tf && (!window_changed || r->core_fresh))
            s = set_tf_parts(r);
        if (s == VF_OK) {
            r->core_fresh = 0;
            r->ms_classify = vfp_now_ms() - t0;
            return VFP_OK;
        }
        if (s != VF_ERR_NOMEM || attempt == 1) {
            snprintf(err, errlen, "%s: %s", r->have_tf ? "cannot apply the transfer function" : "cannot set the window",
                     vf_status_text(s));
            return VFP_ERR;
        }
        size_t needed = vf_renderer_needed_bytes(r->core);
        if (create_core(r, needed + needed / 8, err, errlen))
            return VFP_ERR;
    }
    return VFP_ERR;
}

/* The transfer function to the core, its run-length encoding on the pool's threads: the run lists, and any
 * error, are vf_renderer_set_tf's. */
static vf_status_t set_tf_parts(vfp_render_t *r)
{
    struct vfp_pool *pool = r->pool;
    uint32_t ranges = pool ? RANGES_PER_THREAD * (uint32_t)(pool->workers + 1) : 0;
    if (ranges > VF_MAX_ENCODE_PARTS / 3)
        ranges = VF_MAX_ENCODE_PARTS / 3;
    vf_status_t s = vf_renderer_set_tf_begin(r->core, &r->tf, ranges);
    const uint32_t parts = s == VF_OK ? vf_renderer_encode_parts(r->core) : 0;
    r->tf_parts = parts;
    if (!parts)
        return s; /* encoded whole, or failed, as set_tf */
    frame_work_t *work = &pool->work;
    work->r = r;
    work->job = JOB_ENCODE;
    work->encode_parts = parts;
    work->threads = pool->workers + 1;
    atomic_init(&work->next_part, 0);
    atomic_fetch_add(&pool->posted, 1); /* sequentially consistent: the work above is seen with it */
    wake_all(pool, &pool->posted);
    run_encode(pool, work);
    return vf_renderer_set_tf_end(r->core);
}

static uint32_t table_parts(int threads)
{
    const uint32_t parts = PARTS_PER_THREAD * (uint32_t)threads;
    return parts < VF_MAX_TABLE_PARTS ? parts : VF_MAX_TABLE_PARTS;
}

/* ---------------------------------------------------------------------------------------------------------- */
/* The workers. */

static struct vfp_pool *pool_start(int threads)
{
    struct vfp_pool *pool = aligned_alloc(64, (sizeof *pool + 63) / 64 * 64);
    if (!pool)
        return NULL;
    memset(pool, 0, sizeof *pool);
    atomic_init(&pool->posted, 0);
    atomic_init(&pool->quit, 0);
    atomic_init(&pool->arrived, 0);
    atomic_init(&pool->phase, 0);
    atomic_init(&pool->sleepers, 0);
    for (int d = 0; d < VF_MAX_TABLE; d++)
        atomic_init(&pool->diagonal[d], 0);
    pool->args[0] = (worker_t){pool, 0}; /* the calling thread's, for its copy of the table */
    for (int t = 1; t < threads; t++) {
        pool->args[t] = (worker_t){pool, t};
        if (pthread_create(&pool->ids[t], NULL, worker_main, &pool->args[t]) != 0)
            break; /* fewer threads is slower, not wrong */
        pool->workers = t;
    }
    if (pool->workers == 0) {
        free(pool);
        return NULL;
    }
    return pool;
}

static void pool_stop(struct vfp_pool *pool)
{
    atomic_store(&pool->quit, 1);
    atomic_fetch_add(&pool->posted, 1);
    wake_all(pool, &pool->posted);
    for (int t = 1; t <= pool->workers; t++)
        pthread_join(pool->ids[t], NULL);
    free(pool);
}

static void *worker_main(void *arg)
{
    const worker_t *w = arg;
    struct vfp_pool *pool = w->pool;
    unsigned seen = 0;
    for (;;) {
        wait_while(pool, &pool->posted, seen);
        seen++; /* one post a job (a frame or an encoding): the caller waits for it to end before it posts again */
        if (atomic_load(&pool->quit))
            return NULL;
        if (pool->work.job == JOB_ENCODE)
            run_encode(pool, &pool->work);
        else
            run_frame(pool, &pool->work, w->index);
    }
}

static void fail(atomic_int *status, vf_status_t s)
{
    int expected = VF_OK;
    atomic_compare_exchange_strong(status, &expected, (int)s);
}

/* The next band of a stage, [*y0, *y1) of rows counted by cursor: most rows, or with threads a share of the rows
 * left, at least fewest, so that the last bands are short and the threads finish close together. A band's size
 * follows from its first row alone, so the bands are the same whichever thread takes them. Returns 0 when every
 * row is taken. */
static int next_band(const frame_work_t *work, atomic_uint *cursor, uint32_t rows, uint32_t most, uint32_t fewest,
                     uint32_t *y0, uint32_t *y1)
{
    unsigned at = atomic_load_explicit(cursor, memory_order_relaxed);
    for (;;) {
        if (at >= rows)
            return 0;
        uint32_t left = rows - at, take = most;
        if (work->threads > 1) {
            take = left / (2 * (uint32_t)work->threads);
            take = take > most ? most : take < fewest ? fewest : take;
        }
        take = take < left ? take : left;
        if (atomic_compare_exchange_weak_explicit(cursor, &at, at + take, memory_order_relaxed,
                                                  memory_order_relaxed)) {
            *y0 = at;
            *y1 = at + take;
            return 1;
        }
    }
}

/* A thread's share of a frame. Every thread passes every barrier, a failure included (it only stops the claims),
 * so that none waits for one that left. */
static void run_frame(struct vfp_pool *pool, frame_work_t *work, int index)
{
    vfp_render_t *r = work->r;
    void *scratch = r->scratch[index];
    if (work->table_parts) {
        for (;;) {
            unsigned part = atomic_fetch_add_explicit(&work->next_part, 1, memory_order_relaxed);
            if (part >= work->table_parts || atomic_load(&work->status[FAIL_TABLES]) != VF_OK)
                break;
            vf_status_t s = vf_renderer_build_table_part(r->core, part, scratch, r->scratch_bytes);
            if (s != VF_OK)
                fail(&work->status[FAIL_TABLES], s);
        }
        barrier(pool);
    }
    if (index == 0)
        work->t_tables = vfp_now_ms();
    const vf_thread_table_t copy = {r->table_copy[index], r->table_copy_bytes, fill_diagonal, built_diagonal,
                                    pool ? &pool->args[index] : NULL};
    if (pool && copy.memory) { /* a no-op when the frame's table is shared */
        vf_status_t s = vf_renderer_thread_table_begin(r->core, &copy);
        if (s != VF_OK)
            fail(&work->status[FAIL_BANDS], s);
    }
    uint32_t v0, v1;
    while (atomic_load(&work->status[FAIL_TABLES]) == VF_OK && atomic_load(&work->status[FAIL_BANDS]) == VF_OK &&
           next_band(work, &work->next_row, work->int_rows, BAND_MOST, BAND_FEWEST, &v0, &v1)) {
        vf_status_t s = pool && copy.memory
                            ? vf_renderer_composite_band_in(r->core, v0, v1, scratch, r->scratch_bytes, &copy)
                            : vf_renderer_composite_band(r->core, v0, v1, scratch, r->scratch_bytes);
        if (s != VF_OK)
            fail(&work->status[FAIL_BANDS], s);
    }
    barrier(pool);
    if (index == 0)
        work->t_composite = vfp_now_ms();
    uint32_t y0, y1;
    while (atomic_load(&work->status[FAIL_TABLES]) == VF_OK && atomic_load(&work->status[FAIL_BANDS]) == VF_OK &&
           next_band(work, &work->next_warp, work->out_rows, WARP_MOST, WARP_FEWEST, &y0, &y1)) {
        vf_status_t s = vf_renderer_warp_band(r->core, work->image, y0, y1);
        if (s != VF_OK)
            fail(&work->status[FAIL_BANDS], s);
    }
    barrier(pool); /* the frame ends when every thread has left it: the caller may then change anything */
}

/* A thread's share of an encoding: parts claimed one at a time until none is left. A part only fails for a number
 * out of range, which the counter never gives. */
static void run_encode(struct vfp_pool *pool, frame_work_t *work)
{
    for (;;) {
        unsigned part = atomic_fetch_add_explicit(&work->next_part, 1, memory_order_relaxed);
        if (part >= work->encode_parts)
            break;
        vf_renderer_encode_part(work->r->core, part);
    }
    barrier(pool); /* every part has run when the caller joins them */
}

/* A band of thread w met an unbuilt diagonal of its copy of the table: copied from another thread's copy that has
 * it (true), or left to the core to build (false), claimed first so that the others copy it rather than build it
 * too. When another thread is building it, this one builds it as well rather than wait: the same entries, to the
 * bit, in its own copy. */
static bool fill_diagonal(void *context, uint32_t d)
{
    const worker_t *w = context;
    struct vfp_pool *pool = w->pool;
    const vfp_render_t *r = pool->work.r;
    unsigned state = atomic_load_explicit(&pool->diagonal[d], memory_order_acquire);
    if (state == 0 && atomic_compare_exchange_strong_explicit(&pool->diagonal[d], &state, BUILDING,
                                                              memory_order_acq_rel, memory_order_acquire))
        return false;
    if (!(state & READY))
        return false;
    const int from = (int)(state & 0xFFu);
    const vf_thread_table_t a = {r->table_copy[from], r->table_copy_bytes, NULL, NULL, NULL},
                            b = {r->table_copy[w->index], r->table_copy_bytes, NULL, NULL, NULL};
    return vf_renderer_copy_diagonal(r->core, &a, &b, d) == VF_OK;
}

/* Thread w's copy has diagonal d now: the release makes its entries visible to a thread that reads the state. */
static void built_diagonal(void *context, uint32_t d)
{
    const worker_t *w = context;
    atomic_store_explicit(&w->pool->diagonal[d], READY | (unsigned)w->index, memory_order_release);
}

/* Every thread of the pool waits here until all have come; the last one in lets them go. NULL: one thread. */
static void barrier(struct vfp_pool *pool)
{
    if (!pool)
        return;
    const unsigned phase = atomic_load(&pool->phase); /* it cannot move before this thread arrives */
    if (atomic_fetch_add(&pool->arrived, 1) + 1 == (unsigned)pool->workers + 1) {
        atomic_store(&pool->arrived, 0);
        atomic_fetch_add(&pool->phase, 1);
        wake_all(pool, &pool->phase);
    } else {
        wait_while(pool, &pool->phase, phase);
    }
}

static inline void cpu_relax(void)
{
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#elif defined(__aarch64__) || (defined(__arm__) && defined(__ARM_ARCH) && __ARM_ARCH >= 7)
    __asm__ __volatile__("yield");
#endif
}

/* Wait while *word holds value: poll for up to SPIN_NS (a frame's stages hand over within microseconds, and a
 * futex's sleep and wake-up cost more than that), then sleep on the futex. The sleeper count tells wake_all whether
 * anyone needs the system call; both sides use sequentially consistent operations, so either the waker sees the
 * count or the sleeper sees the new value (the kernel checks it again as it goes to sleep). */
static void wait_while(struct vfp_pool *pool, atomic_uint *word, unsigned value)
{
    double until = 0;
    for (unsigned spins = 0; atomic_load_explicit(word, memory_order_acquire) == value; spins++) {
        if (spins % 64 == 0) {
            double now = vfp_now_ms();
            if (spins == 0)
                until = now + SPIN_NS / 1e6;
            else if (now > until)
                break;
        }
        cpu_relax();
    }
    while (atomic_load(word) == value) {
        atomic_fetch_add(&pool->sleepers, 1);
        if (atomic_load(word) == value)
            syscall(SYS_futex, (unsigned *)word, FUTEX_WAIT_PRIVATE, value, NULL, NULL, 0);
        atomic_fetch_sub(&pool->sleepers, 1);
    }
}

static void wake_all(struct vfp_pool *pool, atomic_uint *word)
{
    if (atomic_load(&pool->sleepers) > 0)
        syscall(SYS_futex, (unsigned *)word, FUTEX_WAKE_PRIVATE, INT_MAX, NULL, NULL, 0);
}
