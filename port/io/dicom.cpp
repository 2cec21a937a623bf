/* SPDX-License-Identifier: MIT */
/*
 * dicom.cpp: the DICOM reader over GDCM, the port layer's one C++ file; its C interface and what it promises are in
 * dicom.h. GDCM parses the files and decodes every transfer syntax it knows (JPEG, JPEG-LS, JPEG 2000, RLE,
 * deflate); this file chooses the series, orders and checks its slices, and fills the volume. Nothing C++ crosses
 * the interface: every failure, an exception included, becomes VFP_ERR with one line in err.
 */

/*********************
 *      INCLUDES
 *********************/
extern "C" {
#include "dicom.h"
#include "volume_internal.h"
}

#include <dirent.h>
#include <fcntl.h>
#include <setjmp.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gdcmAttribute.h>
#include <gdcmDataSet.h>
#include <gdcmImageHelper.h>
#include <gdcmImageReader.h>
#include <gdcmMediaStorage.h>
#include <gdcmReader.h>
#include <gdcmSequenceOfItems.h>
#include <gdcmStringFilter.h>
#include <gdcmTrace.h>

/*********************
 *      DEFINES
 *********************/
namespace {

/* Progress on stderr from this many files on. */
const size_t PROGRESS_FROM = 100;

/* Slices whose steps along the normal differ by more than this share of the usual step (or POSITION_MM) are a gap
 * or an uneven series; positions off the normal by more than this share of a step are a gantry tilt. */
const double STEP_TOLERANCE = 0.05;
const double TILT_TOLERANCE = 0.01;
const double POSITION_MM = 0.01;
/* Image Orientation (Patient) of two slices agree to this in each cosine; rescale values to this relative part. */
const double COSINE_TOLERANCE = 1e-4;
const double RESCALE_TOLERANCE = 1e-6;

const double PI = 3.14159265358979323846;

/**********************
 *      TYPES
 **********************/

/* One slice: a single-frame file, or one frame of a multi-frame file. */
struct Slice {
    std::string file;
    unsigned frame = 0;       /* frame in its file (0 for single-frame files) */
    unsigned frames = 1;      /* frames in its file */
    std::string series, description;
    bool has_position = false, has_orientation = false;
    double position[3] = {0, 0, 0};
    double orientation[6] = {1, 0, 0, 0, 1, 0};
    double pixel_spacing[2] = {1, 1}; /* rows apart (y), columns apart (x), as (0028,0030) orders them */
    double slope = 1, inter = 0;
    unsigned rows = 0, columns = 0, bits = 0, samples = 1, sign = 0;
    double along = 0;         /* position along the series' normal */
};

/* Where a GDCM call that fails an assertion comes back to (guarded). */
sigjmp_buf gdcm_abort;

/* A failure with its line of text, thrown inside this file and caught at the C interface. */
struct Failure {
    std::string text;
};

/**********************
 *  STATIC PROTOTYPES
 **********************/
[[noreturn]] void fail(const std::string &name, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
std::vector<std::string> folder_files(const std::string &dir);
bool read_slices(const std::string &file, std::vector<Slice> &out);
void load(vfp_volume_t *vol, const std::string &path, const vfp_load_opts_t *opts);
std::vector<Slice> choose_series(const std::string &path, std::vector<Slice> &slices, const std::string &wanted,
                                 const std::string &of_file, bool quiet);
void order_and_check(std::vector<Slice> &s, double normal[3], double *step);
void read_pixels(vfp_volume_t *vol, const std::vector<Slice> &s, const std::string &path, bool quiet);
std::string shown(const std::string &text);
template <class F> bool guarded(F &&call);

/**********************
 *      CLASSES
 **********************/

/* "PATH: reading 456 DICOM files: 123" updated in place on a terminal, or a line at every quarter otherwise. */
class Progress {
  public:
    Progress(const std::string &path, const char *what, size_t total, bool quiet)
        : path_(path), what_(what), total_(total), on_(!quiet && total >= PROGRESS_FROM), tty_(isatty(2) != 0)
    {
    }
    void step(size_t done)
    {
        if (!on_)
            return;
        if (tty_) {
            std::fprintf(stderr, "\r%s: %s %zu/%zu", path_.c_str(), what_, done, total_);
            if (done == total_)
                std::fputc('\n', stderr);
        } else if (done * 4 / total_ != (done - 1) * 4 / total_ || done == 1) {
            std::fprintf(stderr, "%s: %s %zu/%zu\n", path_.c_str(), what_, done, total_);
        }
        std::fflush(stderr);
    }

  private:
    std::string path_;
    const char *what_;
    size_t total_;
    bool on_, tty_;
};

} // namespace

/**********************
 *   GLOBAL FUNCTIONS
 **********************/

extern "C" vfp_status_t vfpi_load_dicom(vfp_volume_t *vol, const char *path, const vfp_load_opts_t *opts, char *err,
                                        size_t errlen)
{
    try {
        load(vol, path, opts);
        return VFP_OK;
    } catch (const Failure &f) {
        free(vol->data);
        vol->data = nullptr;
        if (err && errlen)
            snprintf(err, errlen, "%s", f.text.c_str());
        return VFP_ERR;
    } catch (const std::bad_alloc &) {
        free(vol->data);
        vol->data = nullptr;
        return vfpi_fail(err, errlen, path, 0, "out of memory reading DICOM");
    } catch (...) {
        free(vol->data);
        vol->data = nullptr;
        return vfpi_fail(err, errlen, path, 0, "GDCM failed reading DICOM");
    }
}

/**********************
 *   STATIC FUNCTIONS
 **********************/
namespace {

void fail(const std::string &name, const char *fmt, ...)
{
    char msg[VFP_ERR_LEN];
    va_list ap;
    va_start(ap, fmt);
    std::vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    char line[VFP_ERR_LEN];
    vfpi_fail(line, sizeof line, name.c_str(), 0, "%s", msg); /* printable, as every reader's message */
    throw Failure{line};
}

/* A description or UID as a message shows it: at most 64 characters. */
void on_gdcm_abort(int)
{
    siglongjmp(gdcm_abort, 1);
}

/* Runs one GDCM call and returns what it returns, or false if it aborted. Debian's GDCM is built with assertions,
 * and a file that ends inside a data element (a copy cut short) fails one (abort) where the reader would otherwise
 * return false: so SIGABRT comes back here, and stderr, where the assertion prints its message, goes to /dev/null
 * during the call, which keeps the error to this reader's one line. Both are process-wide for the call's length:
 * volumes load on one thread, before anything else writes to stderr. The aborted call's objects are not destroyed
 * (a few kilobytes and a file descriptor per such file). */
template <class F> bool guarded(F &&call)
{
    std::fflush(stderr);
    int saved = dup(2), null = open("/dev/null", O_WRONLY);
    if (saved >= 0 && null >= 0)
        dup2(null, 2);
    struct sigaction on = {}, old = {};
    on.sa_handler = on_gdcm_abort;
    sigemptyset(&on.sa_mask);
    sigaction(SIGABRT, &on, &old);
    volatile bool ok = false;
    if (sigsetjmp(gdcm_abort, 1) == 0)
        ok = call();
    sigaction(SIGABRT, &old, nullptr);
    if (saved >= 0 && null >= 0)
        dup2(saved, 2);
    if (saved >= 0)
        close(saved);
    if (null >= 0)
        close(null);
    return ok;
}

std::string shown(const std::string &text)
{
    return text.size() > 64 ? text.substr(0, 61) + "..." : text;
}

/* The regular files of a folder (not its subfolders), sorted by name so that every run sees them in one order. */
std::vector<std::string> folder_files(const std::string &dir)
{
    std::vector<std::string> files;
    DIR *d = opendir(dir.c_str());
    if (!d)
        fail(dir, "cannot open the folder: %s", std::strerror(errno));
    while (struct dirent *e = readdir(d)) {
        if (e->d_name[0] == '.')
            continue;
        std::string f = dir + (dir.empty() || dir.back() == '/' ? "" : "/") + e->d_name;
        struct stat st;
        if (stat(f.c_str(), &st) == 0 && S_ISREG(st.st_mode))
            files.push_back(f);
    }
    closedir(d);
    std::sort(files.begin(), files.end());
    return files;
}

template <uint16_t G, uint16_t E> bool has(const gdcm::DataSet &ds)
{
    return ds.FindDataElement(gdcm::Tag(G, E)) && !ds.GetDataElement(gdcm::Tag(G, E)).IsEmpty();
}

/* The item `index` (1-based) of a sequence in ds, or nullptr. */
const gdcm::DataSet *item(const gdcm::DataSet &ds, const gdcm::Tag &tag, size_t index)
{
    if (!ds.FindDataElement(tag))
        return nullptr;
    gdcm::SmartPointer<gdcm::SequenceOfItems> sq = ds.GetDataElement(tag).GetValueAsSQ();
    if (!sq || sq->GetNumberOfItems() < index)
        return nullptr;
    return &sq->GetItem(index).GetNestedDataSet();
}

/* A functional group's macro for a frame: the per-frame one, else the shared one (enhanced multi-frame IODs). */
const gdcm::DataSet *group(const gdcm::DataSet &ds, unsigned frame, const gdcm::Tag &macro)
{
    const gdcm::Tag per_frame(0x5200, 0x9230), shared(0x5200, 0x9229);
    if (const gdcm::DataSet *f = item(ds, per_frame, frame + 1))
        if (const gdcm::DataSet *m = item(*f, macro, 1))
            return m;
    if (const gdcm::DataSet *s = item(ds, shared, 1))
        if (const gdcm::DataSet *m = item(*s, macro, 1))
            return m;
    return nullptr;
}

/* Reads the header of a file (up to the pixel data) into one slice per frame; false if it is no DICOM image. */
bool read_slices(const std::string &file, std::vector<Slice> &out)
{
    gdcm::Reader reader;
    reader.SetFileName(file.c_str());
    if (!guarded([&] { return reader.ReadUpToTag(gdcm::Tag(0x7fe0, 0x0010)); }))
        return false;
    const gdcm::File &f = reader.GetFile();
    const gdcm::DataSet &ds = f.GetDataSet();
    if (!has<0x0028, 0x0010>(ds) || !has<0x0028, 0x0011>(ds))
        return false; /* not an image: a DICOMDIR, a report, a presentation state */
    gdcm::StringFilter sf;
    sf.SetFile(f);
    Slice s;
    s.file = file;
    s.series = sf.ToString(gdcm::Tag(0x0020, 0x000e));
    s.description = sf.ToString(gdcm::Tag(0x0008, 0x103e));
    for (std::string *t : {&s.series, &s.description}) /* DICOM pads strings to even lengths */
        while (!t->empty() && (t->back() == ' ' || t->back() == '\0'))
            t->pop_back();
    gdcm::Attribute<0x0028, 0x0010> rows;
    gdcm::Attribute<0x0028, 0x0011> columns;
    gdcm::Attribute<0x0028, 0x0100> bits;
    gdcm::Attribute<0x0028, 0x0103> sign;
    gdcm::Attribute<0x0028, 0x0002> samples;
    rows.SetFromDataSet(ds);
    columns.SetFromDataSet(ds);
    s.rows = rows.GetValue();
    s.columns = columns.GetValue();
    if (has<0x0028, 0x0100>(ds)) {
        bits.SetFromDataSet(ds);
        s.bits = bits.GetValue();
    }
    if (has<0x0028, 0x0103>(ds)) {
        sign.SetFromDataSet(ds);
        s.sign = sign.GetValue();
    }
    if (has<0x0028, 0x0002>(ds)) {
        samples.SetFromDataSet(ds);
        s.samples = samples.GetValue();
    }
    unsigned frames = 1;
    if (has<0x0028, 0x0008>(ds)) {
        std::string n = sf.ToString(gdcm::Tag(0x0028, 0x0008));
        long v = std::strtol(n.c_str(), nullptr, 10);
        if (v < 1 || v > VF_MAX_DIM)
            fail(file, "(0028,0008) Number of Frames '%s' is out of range (expected 1..%d)", shown(n).c_str(),
                 VF_MAX_DIM);
        frames = (unsigned)v;
    }
    s.frames = frames;

    /* Single-frame: the plain attributes. */
    if (has<0x0020, 0x0032>(ds)) {
        gdcm::Attribute<0x0020, 0x0032> ipp;
        ipp.SetFromDataSet(ds);
        for (int i = 0; i < 3; i++)
            s.position[i] = ipp.GetValue(i);
        s.has_position = true;
    }
    if (has<0x0020, 0x0037>(ds)) {
        gdcm::Attribute<0x0020, 0x0037> iop;
        iop.SetFromDataSet(ds);
        for (int i = 0; i < 6; i++)
            s.orientation[i] = iop.GetValue(i);
        s.has_orientation = true;
    }
    if (has<0x0028, 0x0030>(ds)) {
        gdcm::Attribute<0x0028, 0x0030> ps;
        ps.SetFromDataSet(ds);
        s.pixel_spacing[0] = ps.GetValue(0);
        s.pixel_spacing[1] = ps.GetValue(1);
    }
    if (has<0x0028, 0x1053>(ds)) {
        gdcm::Attribute<0x0028, 0x1053> slope;
        slope.SetFromDataSet(ds);
        s.slope = slope.GetValue();
    }
    if (has<0x0028, 0x1052>(ds)) {
        gdcm::Attribute<0x0028, 0x1052> inter;
        inter.SetFromDataSet(ds);
        s.inter = inter.GetValue();
    }

    /* Multi-frame: each frame's position, orientation, spacing and rescale from the functional groups (enhanced
     * CT and MR); without them, GDCM's reading of the legacy attributes and the frames evenly spaced. */
    for (unsigned k = 0; k < frames; k++) {
        Slice t = s;
        t.frame = k;
        if (frames > 1) {
            if (const gdcm::DataSet *m = group(ds, k, gdcm::Tag(0x0020, 0x9113))) { /* Plane Position */
                if (has<0x0020, 0x0032>(*m)) {
                    gdcm::Attribute<0x0020, 0x0032> ipp;
                    ipp.SetFromDataSet(*m);
                    for (int i = 0; i < 3; i++)
                        t.position[i] = ipp.GetValue(i);
                    t.has_position = true;
                }
            } else {
                std::vector<double> origin = gdcm::ImageHelper::GetOriginValue(f);
                std::vector<double> spacing = gdcm::ImageHelper::GetSpacingValue(f);
                std::vector<double> cosines = gdcm::ImageHelper::GetDirectionCosinesValue(f);
                if (origin.size() >= 3 && spacing.size() >= 3 && cosines.size() >= 6) {
                    double n[3] = {cosines[1] * cosines[5] - cosines[2] * cosines[4],
                                   cosines[2] * cosines[3] - cosines[0] * cosines[5],
                                   cosines[0] * cosines[4] - cosines[1] * cosines[3]};
                    for (int i = 0; i < 3; i++)
                        t.position[i] = origin[i] + k * spacing[2] * n[i];
                    t.has_position = s.has_position || has<0x0020, 0x0032>(ds);
                }
            }
            if (const gdcm::DataSet *m = group(ds, k, gdcm::Tag(0x0020, 0x9116))) { /* Plane Orientation */
                if (has<0x0020, 0x0037>(*m)) {
                    gdcm::Attribute<0x0020, 0x0037> iop;
                    iop.SetFromDataSet(*m);
                    for (int i = 0; i < 6; i++)
                        t.orientation[i] = iop.GetValue(i);
                    t.has_orientation = true;
                }
            }
            if (const gdcm::DataSet *m = group(ds, k, gdcm::Tag(0x0028, 0x9110))) { /* Pixel Measures */
                if (has<0x0028, 0x0030>(*m)) {
                    gdcm::Attribute<0x0028, 0x0030> ps;
                    ps.SetFromDataSet(*m);
                    t.pixel_spacing[0] = ps.GetValue(0);
                    t.pixel_spacing[1] = ps.GetValue(1);
                }
            }
            if (const gdcm::DataSet *m = group(ds, k, gdcm::Tag(0x0028, 0x9145))) { /* Pixel Value Transformation */
                if (has<0x0028, 0x1053>(*m)) {
                    gdcm::Attribute<0x0028, 0x1053> slope;
                    slope.SetFromDataSet(*m);
                    t.slope = slope.GetValue();
                }
                if (has<0x0028, 0x1052>(*m)) {
                    gdcm::Attribute<0x0028, 0x1052> inter;
                    inter.SetFromDataSet(*m);
                    t.inter = inter.GetValue();
                }
            }
        }
        out.push_back(t);
    }
    return true;
}

void load(vfp_volume_t *vol, const std::string &path, const vfp_load_opts_t *opts)
{
    /* GDCM prints its own warnings and errors to stderr (a multi-frame file's spacing it cannot compute, a private
     * tag it does not know), which would break the one-line errors the programs promise: this reader says what
     * matters itself. The switches are GDCM's process-wide ones; nothing else in volfix uses GDCM. */
    gdcm::Trace::SetDebug(false);
    gdcm::Trace::SetWarning(false);
    gdcm::Trace::SetError(false);
    bool quiet = opts && opts->quiet;
    std::string wanted = opts && opts->series ? opts->series : "";
    struct stat st;
    if (stat(path.c_str(), &st) != 0)
        fail(path, "cannot open: %s", std::strerror(errno));

    /* A folder: every file in it. A single file: itself when it is a multi-frame image; a slice of a series is
     * loaded with the rest of its series from its folder. */
    std::vector<Slice> slices;
    std::string folder = path, of_file;
    size_t skipped = 0; /* files in the folder that are no DICOM image */
    if (S_ISDIR(st.st_mode)) {
        std::vector<std::string> files = folder_files(path);
        Progress progress(path, "reading DICOM headers", files.size(), quiet);
        for (size_t i = 0; i < files.size(); i++) {
            if (!read_slices(files[i], slices))
                skipped++;
            progress.step(i + 1);
        }
        if (slices.empty())
            fail(path, "is a directory with no DICOM images in it (%zu file%s%s; expected a volume file or a folder of "
                 "DICOM slices)", files.size(), files.size() == 1 ? "" : "s", skipped ? ", none readable by GDCM" : "");
    } else {
        if (!read_slices(path, slices))
            fail(path, "not a DICOM image that GDCM can read (expected a DICOM file with Rows, Columns and pixel "
                 "data)");
        if (slices[0].frames == 1) {
            size_t slash = path.rfind('/');
            folder = slash == std::string::npos ? "." : slash == 0 ? "/" : path.substr(0, slash);
            of_file = slices[0].series;
            if (wanted.empty())
                wanted = of_file;
            slices.clear();
            std::vector<std::string> files = folder_files(folder);
            Progress progress(folder, "reading DICOM headers", files.size(), quiet);
            for (size_t i = 0; i < files.size(); i++) {
                read_slices(files[i], slices);
                progress.step(i + 1);
            }
        }
    }
    std::vector<Slice> series = choose_series(folder, slices, wanted, of_file, quiet);
    const Slice &first = series[0];
    if (first.samples != 1)
        fail(first.file, "(0028,0002) Samples per Pixel %u: colour images are not supported (expected 1, grey)",
             first.samples);
    if (first.bits != 8 && first.bits != 16)
        fail(first.file, "(0028,0100) Bits Allocated %u is not supported (expected 8 or 16)", first.bits);
    double normal[3], step = 1;
    order_and_check(series, normal, &step);

    /* x runs along a row (the first cosines), y down the columns, z along the normal towards the later slices. */
    uint64_t d[3] = {series[0].columns, series[0].rows, series.size()};
    if (vfpi_check_dims(d, path.c_str(), 0, nullptr, 0) != VFP_OK) {
        if (series.size() < 2)
            fail(path, "series %s has one slice: a volume needs at least 2", shown(first.series).c_str());
        fail(path, "%llux%llux%llu voxels are out of range (expected 2..%d along each axis)",
             (unsigned long long)d[0], (unsigned long long)d[1], (unsigned long long)d[2], VF_MAX_DIM);
    }
    double spacing[3] = {first.pixel_spacing[1], first.pixel_spacing[0], step};
    for (int a = 0; a < 3; a++)
        if (vfpi_check_spacing(spacing[a], a, first.file.c_str(), 0, nullptr, 0) != VFP_OK)
            fail(first.file, "%s %g along %c is not a voxel size (expected a number > 0 and <= %g)",
                 a < 2 ? "(0028,0030) Pixel Spacing" : "the slices' step", spacing[a], "xyz"[a], VFPI_MAX_SPACING);
    for (int a = 0; a < 3; a++)
        vol->spacing[a] = spacing[a];
    vol->slope = first.slope;
    vol->inter = first.inter;
    double axes[3][3] = {{first.orientation[0], first.orientation[1], first.orientation[2]},
                         {first.orientation[3], first.orientation[4], first.orientation[5]},
                         {normal[0], normal[1], normal[2]}};
    char err[VFP_ERR_LEN];
    if (first.has_orientation &&
        vfpi_set_direction(vol, axes, "Image Orientation (Patient)", first.file.c_str(), 0, err, sizeof err))
        throw Failure{err};
    read_pixels(vol, series, path, quiet);
}

/* The series to load: the one asked for, else the one with the most slices (the first UID of the largest on a tie),
 * and a line on stderr for each of the others. */
std::vector<Slice> choose_series(const std::string &path, std::vector<Slice> &slices, const std::string &wanted,
                                 const std::string &of_file, bool quiet)
{
    std::map<std::string, std::vector<Slice>> by_uid;
    for (Slice &s : slices)
        by_uid[s.series].push_back(s);
    std::string pick;
    if (!wanted.empty()) {
        if (!by_uid.count(wanted)) {
            std::string list;
            for (auto &kv : by_uid)
                list += (list.empty() ? "" : ", ") + shown(kv.first);
            fail(path, "--series %s: no such series here (the series are: %s)", shown(wanted).c_str(),
                 list.c_str());
        }
        pick = wanted;
    } else {
        for (auto &kv : by_uid)
            if (pick.empty() || kv.second.size() > by_uid[pick].size())
                pick = kv.first;
    }
    if (!quiet && by_uid.size() > 1) {
        std::fprintf(stderr, "%s: %zu series; loading %s \"%s\" (%zu slices)%s\n", path.c_str(), by_uid.size(),
                     shown(pick).c_str(), shown(by_uid[pick][0].description).c_str(), by_uid[pick].size(),
                     pick == of_file ? ", the file's own" : wanted.empty() ? ", the largest" : "");
        for (auto &kv : by_uid)
            if (kv.first != pick)
                std::fprintf(stderr, "%s: other series %s \"%s\" (%zu slices): --series %s loads it\n", path.c_str(),
                             shown(kv.first).c_str(), shown(kv.second[0].description).c_str(), kv.second.size(),
                             shown(kv.first).c_str());
    }
    return by_uid[pick];
}

/* Sorts the slices along their normal and checks that they make one regular volume: one size, type, orientation
 * and rescale; positions evenly spaced (no gap: a missing slice) and along the normal (no gantry tilt). */
void order_and_check(std::vector<Slice> &s, double normal[3], double *step)
{
    const Slice &a = s[0];
    for (const Slice &b : s) {
        if (b.rows != a.rows || b.columns != a.columns)
            fail(b.file, "(0028,0010) Rows, (0028,0011) Columns %ux%u differ from %s's %ux%u (expected one size for "
                 "the series)", b.columns, b.rows, a.file.c_str(), a.columns, a.rows);
        if (b.bits != a.bits || b.sign != a.sign || b.samples != a.samples)
            fail(b.file, "(0028,0100) Bits Allocated or (0028,0103) Pixel Representation differ from %s's (expected one "
                 "pixel type for the series)", a.file.c_str());
        if (std::fabs(b.slope - a.slope) > RESCALE_TOLERANCE * std::max(1.0, std::fabs(a.slope)) ||
            std::fabs(b.inter - a.inter) > RESCALE_TOLERANCE * std::max(1.0, std::fabs(a.inter)))
            fail(b.file, "(0028,1053) Rescale Slope %g, (0028,1052) Rescale Intercept %g differ from %s's %g, %g "
                 "(one rescale for the whole series is supported)", b.slope, b.inter, a.file.c_str(), a.slope,
                 a.inter);
        for (int i = 0; i < 6; i++)
            if (std::fabs(b.orientation[i] - a.orientation[i]) > COSINE_TOLERANCE)
                fail(b.file, "(0020,0037) Image Orientation (Patient) differs from %s's (expected one orientation for "
                     "the series)", a.file.c_str());
    }
    const double *r = a.orientation, *c = a.orientation + 3;
    normal[0] = r[1] * c[2] - r[2] * c[1];
    normal[1] = r[2] * c[0] - r[0] * c[2];
    normal[2] = r[0] * c[1] - r[1] * c[0];
    double len = std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
    if (!(len > 0.5))
        fail(a.file, "(0020,0037) Image Orientation (Patient) is not two perpendicular unit vectors");
    for (int i = 0; i < 3; i++)
        normal[i] /= len;
    if (s.size() < 2) {
        *step = a.pixel_spacing[0];
        return;
    }
    for (Slice &b : s) {
        if (!b.has_position)
            fail(b.file, "no (0020,0032) Image Position (Patient): the slices cannot be put in order (expected CT or MR "
                 "slices with positions)");
        b.along = b.position[0] * normal[0] + b.position[1] * normal[1] + b.position[2] * normal[2];
    }
    std::stable_sort(s.begin(), s.end(), [](const Slice &x, const Slice &y) { return x.along < y.along; });
    std::vector<double> steps;
    for (size_t i = 1; i < s.size(); i++) {
        double d = s[i].along - s[i - 1].along;
        if (d < POSITION_MM)
            fail(s[i].file, "(0020,0032) Image Position (Patient) is the same as %s's (two slices at one place: a "
                 "repeated file, or two acquisitions in one series)", s[i - 1].file.c_str());
        steps.push_back(d);
    }
    std::vector<double> sorted = steps;
    std::sort(sorted.begin(), sorted.end());
    double usual = sorted[sorted.size() / 2];
    for (size_t i = 1; i < s.size(); i++) {
        double d = steps[i - 1];
        if (std::fabs(d - usual) > std::max(POSITION_MM, STEP_TOLERANCE * usual))
            fail(s[i].file, "(0020,0032) Image Position (Patient) is %.4g mm after %s's, where the slices are %.4g mm "
                 "apart: %s (uneven slices are not supported)", d, s[i - 1].file.c_str(), usual,
                 d > 1.5 * usual ? "a missing slice" : "uneven spacing");
        /* The step's part across the normal: zero when the slices are stacked along it. */
        double side = 0;
        for (int k = 0; k < 3; k++) {
            double across = s[i].position[k] - s[i - 1].position[k] - d * normal[k];
            side += across * across;
        }
        side = std::sqrt(side);
        if (side > std::max(POSITION_MM, TILT_TOLERANCE * d))
            fail(s[i].file, "(0020,0032) Image Position (Patient) moves %.3g mm sideways for %.3g mm along the normal "
                 "of (0020,0037) Image Orientation (Patient): a gantry tilt of %.1f degrees (slices that are not "
                 "stacked along their normal are not supported)", side, d, std::atan2(side, d) * 180 / PI);
    }
    *step = (s.back().along - s.front().along) / (double)(s.size() - 1);
}

/* The pixels of every slice, decoded by GDCM, into one volume: slice k of the sorted series is z = k. */
void read_pixels(vfp_volume_t *vol, const std::vector<Slice> &s, const std::string &path, bool quiet)
{
    const Slice &a = s[0];
    unsigned bytes = a.bits / 8;
    size_t slice_bytes = (size_t)a.rows * a.columns * bytes;
    vol->core.dims[0] = a.columns;
    vol->core.dims[1] = a.rows;
    vol->core.dims[2] = (uint32_t)s.size();
    vol->core.type = bytes == 1 ? (a.sign ? VF_VOXEL_I8 : VF_VOXEL_U8) : (a.sign ? VF_VOXEL_I16 : VF_VOXEL_U16);
    vol->data = std::malloc(slice_bytes * s.size());
    if (!vol->data)
        fail(path, "out of memory for %zu bytes of voxels", slice_bytes * s.size());
    /* Each file once, in the order of its first slice; a multi-frame file fills all its slices. */
    std::map<std::string, std::vector<std::pair<unsigned, size_t>>> frames_of; /* file: (frame, z) */
    std::vector<std::string> order;
    for (size_t z = 0; z < s.size(); z++) {
        if (!frames_of.count(s[z].file))
            order.push_back(s[z].file);
        frames_of[s[z].file].emplace_back(s[z].frame, z);
    }
    Progress progress(path, "decoding DICOM slices", order.size(), quiet);
    std::vector<char> buffer;
    for (size_t i = 0; i < order.size(); i++) {
        const std::string &file = order[i];
        gdcm::ImageReader reader;
        reader.SetFileName(file.c_str());
        /* GDCM reads pixel data that the file cuts short as if it were there (zeros) and only warns: its warning
         * is caught here and made the error it is. */
        std::ostringstream warnings;
        std::ostream &was = gdcm::Trace::GetWarningStream();
        gdcm::Trace::SetWarningStream(warnings);
        gdcm::Trace::SetWarning(true);
        bool read = guarded([&] { return reader.Read(); });
        gdcm::Trace::SetWarning(false);
        gdcm::Trace::SetWarningStream(was);
        if (!read)
            fail(file, "GDCM cannot read this image (a file cut short, or not an image GDCM knows)");
        if (warnings.str().find("Incomplete Pixel Data") != std::string::npos)
            fail(file, "(7fe0,0010) Pixel Data is cut short: the file ends before the image does (a copy cut short?)");
        const gdcm::Image &image = reader.GetImage();
        const gdcm::PixelFormat &pf = image.GetPixelFormat();
        if (pf.GetBitsAllocated() != a.bits || pf.GetSamplesPerPixel() != 1)
            fail(file, "(0028,0100) Bits Allocated %u after decoding (expected %u)", (unsigned)pf.GetBitsAllocated(),
                 a.bits);
        unsigned long length = image.GetBufferLength();
        size_t frames = frames_of[file].size() > 1 || s[frames_of[file][0].second].frames > 1
                            ? s[frames_of[file][0].second].frames : 1;
        if (length < slice_bytes * frames)
            fail(file, "(7fe0,0010) Pixel Data holds %lu bytes (expected %zu for %u x %u x %zu frame%s of %u bits)",
                 length, slice_bytes * frames, a.columns, a.rows, frames, frames == 1 ? "" : "s", a.bits);
        buffer.resize(length);
        if (!guarded([&] { return image.GetBuffer(buffer.data()); }))
            fail(file, "(7fe0,0010) Pixel Data cannot be decoded (transfer syntax %s)",
                 gdcm::TransferSyntax::GetTSString(image.GetTransferSyntax()));
        for (const auto &fz : frames_of[file])
            std::memcpy((char *)vol->data + fz.second * slice_bytes, buffer.data() + (size_t)fz.first * slice_bytes,
                        slice_bytes);
        progress.step(i + 1);
    }
}

} // namespace
