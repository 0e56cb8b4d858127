// CheckMatLayout: a MAT v5 file walked element by element before libmatio reads it; a MAT v7.3
// file opened by HDF5 first; a MAT v4 file's headers compared with its size.
//
// Why: libmatio 1.5.23 sizes a variable's buffer from the dims the file declares and then reads
// whatever the data element holds, without comparing the two. A variable declaring 1x8 doubles
// whose data element holds 3 came back with 5 values of uninitialised heap (or, when more
// variables followed, the next variable's bytes, or the previous buffer's values), exit 0; matio
// logs nothing and reports no error. Only the file itself says how many values it stores (the
// data element's byte count), so it is read here, independently of matio: every variable's
// stored element count must equal the product of its dims. Zero-filling matio's buffer would
// hide the corruption, not fix it.
// Long file: the MAT layout walk of each version (v5 elements, v4 headers, v7.3 through HDF5)
// beside the one entry point that tells them apart; read together when a fuzzer finds a file.
#include <fmt/format.h>
#include <hdf5.h>
#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/json_text.hpp"
#include "io/container_policy.hpp"
#include "io/containers.hpp"
#include "sysid/error.hpp"

namespace sysid::internal {
namespace {

// MAT v5 data types (the first word of a data element's tag).
constexpr std::uint32_t kMiInt8 = 1, kMiUint8 = 2, kMiInt16 = 3, kMiUint16 = 4, kMiInt32 = 5,
                        kMiUint32 = 6, kMiSingle = 7, kMiDouble = 9, kMiInt64 = 12, kMiUint64 = 13,
                        kMiMatrix = 14, kMiCompressed = 15, kMiUtf16 = 17;
// MAT v5 array classes (the low byte of the array flags).
constexpr std::uint32_t kCell = 1, kStruct = 2, kObject = 3, kChar = 4, kFirstNumeric = 6,
                        kLastNumeric = 15;
constexpr std::uint32_t kComplexFlag = 0x0800;
// Bytes of one element of a numeric MAT data type, 0 for any other type.
std::uint64_t NumericSize(std::uint32_t type) {
  switch (type) {
    case kMiInt8:
    case kMiUint8:
      return 1;
    case kMiInt16:
    case kMiUint16:
      return 2;
    case kMiInt32:
    case kMiUint32:
    case kMiSingle:
      return 4;
    case kMiDouble:
    case kMiInt64:
    case kMiUint64:
      return 8;
    default:
      return 0;
  }
}

// Thrown by a source that reached an inflate bound (container_policy.hpp): the file is refused,
// never left unchecked.
struct InflateBound {
  bool whole_file = false;
};

// The bytes of one variable: a span of the file, or the inflated stream of a compressed one.
class ByteSource {
 public:
  virtual ~ByteSource() = default;
  /// Exactly `n` bytes; false when the data end first (or are corrupt: see Problem()).
  virtual bool Read(unsigned char* out, std::size_t n) = 0;
  virtual bool Skip(std::uint64_t n) = 0;
  /// Why the last Read or Skip failed, for the message.
  virtual std::string Problem() const = 0;
};

class FileSpan : public ByteSource {
 public:
  explicit FileSpan(std::FILE* f) : f_(f) {}
  bool Read(unsigned char* out, std::size_t n) override { return std::fread(out, 1, n, f_) == n; }
  bool Skip(std::uint64_t n) override {
    // Bounds were checked against the file's size by the caller: a seek is enough.
    return fseeko(f_, static_cast<off_t>(n), SEEK_CUR) == 0;
  }
  std::string Problem() const override { return "the file ends"; }

 private:
  std::FILE* f_;
};

// zlib's stream over the compressed element's bytes (`in_left` of them from the file's current
// position), inflated on demand; `*file_total` counts the bytes inflated from the whole file.
class InflatedSpan : public ByteSource {
 public:
  InflatedSpan(std::FILE* f, std::uint64_t in_left, std::uint64_t* file_total)
      : f_(f), in_left_(in_left), file_total_(file_total) {
    if (inflateInit(&z_) != Z_OK)
      problem_ = "zlib cannot start";
    else
      started_ = true;
  }
  ~InflatedSpan() override {
    if (started_) inflateEnd(&z_);
  }
  InflatedSpan(const InflatedSpan&) = delete;
  InflatedSpan& operator=(const InflatedSpan&) = delete;

  bool Read(unsigned char* out, std::size_t n) override {
    if (!started_) return false;
    total_ += n;
    *file_total_ += n;
    if (total_ > kMaxInflatedVariableBytes) throw InflateBound{false};
    if (*file_total_ > kMaxInflatedFileBytes) throw InflateBound{true};
    z_.next_out = out;
    z_.avail_out = static_cast<uInt>(n);
    while (z_.avail_out > 0) {
      if (ended_) {
        problem_ = "the compressed data end";
        return false;
      }
      if (z_.avail_in == 0 && in_left_ > 0) {
        const std::size_t k =
            static_cast<std::size_t>(std::min<std::uint64_t>(sizeof in_, in_left_));
        if (std::fread(in_, 1, k, f_) != k) {
          problem_ = "the file ends";
          return false;
        }
        in_left_ -= k;
        z_.next_in = in_;
        z_.avail_in = static_cast<uInt>(k);
      }
      const int r = inflate(&z_, Z_NO_FLUSH);
      if (r == Z_STREAM_END) {
        ended_ = true;
      } else if (r == Z_BUF_ERROR) {  // no progress possible: the input ran out
        problem_ = "the compressed data end";
        return false;
      } else if (r != Z_OK) {
        problem_ =
            std::string("corrupt compressed data (zlib: ") + (z_.msg ? z_.msg : "error") + ")";
        return false;
      }
    }
    return true;
  }
  bool Skip(std::uint64_t n) override {
    unsigned char scratch[16384];
    while (n > 0) {
      const std::size_t k = static_cast<std::size_t>(std::min<std::uint64_t>(sizeof scratch, n));
      if (!Read(scratch, k)) return false;
      n -= k;
    }
    return true;
  }
  std::string Problem() const override { return problem_; }

 private:
  std::FILE* f_;
  std::uint64_t in_left_;
  std::uint64_t* file_total_;
  z_stream z_{};
  unsigned char in_[16384];
  bool started_ = false, ended_ = false;
  std::uint64_t total_ = 0;
  std::string problem_;
};

// A data element's tag. A small element (its type and size packed in the first word, at most 4
// bytes of data in the second) is read whole: `small` holds its data.
struct Tag {
  std::uint32_t type = 0;
  std::uint64_t bytes = 0;
  bool is_small = false;
  unsigned char small[4] = {};
};

class LayoutChecker {
 public:
  LayoutChecker(std::string path, bool little_endian)
      : path_(std::move(path)), little_(little_endian) {}

  std::uint32_t U32(const unsigned char* b) const {
    return little_ ? (std::uint32_t{b[0]} | std::uint32_t{b[1]} << 8 | std::uint32_t{b[2]} << 16 |
                      std::uint32_t{b[3]} << 24)
                   : (std::uint32_t{b[3]} | std::uint32_t{b[2]} << 8 | std::uint32_t{b[1]} << 16 |
                      std::uint32_t{b[0]} << 24);
  }

  // "a.mat:x: malformed or truncated MAT file: declares 1x8 (8 elements), holds 3"; before a
  // variable's name is read, "a.mat: malformed ...: at byte 128: ..." (prefix_).
  [[noreturn]] void Fail(const std::string& where, const std::string& detail) const {
    throw InputError(where + ": malformed or truncated MAT file: " + prefix_ + detail);
  }
  void SetPrefix(std::string prefix) {
    prefix_ = std::move(prefix);
    current_ = path_;
  }
  /// The variable being checked, as messages name it ("a.mat:u"; the file before its name).
  const std::string& current() const { return current_; }

  // One miMATRIX element's content (`avail` bytes, its tag already read), consumed whole.
  // `where` names it in messages until its name is known ("a.mat:x", "a.mat:s.Y(2).Data").
  void Matrix(ByteSource& src, std::uint64_t avail, std::string where, bool top, int depth) {
    // Before anything of it is read: matio allocates a variable for each, [] included.
    budget_.Count(where);
    budget_.Depth(depth, where);
    if (avail == 0) return;  // an empty placeholder (a cell or field holding [])
    // Array flags: class, complex bit.
    unsigned char flags[8] = {};
    Tag t = Sub(src, avail, where, "the array flags");
    if (t.type != kMiUint32 || t.bytes < 8) Fail(where, "no array flags where they belong");
    Content(src, t, avail, where, flags, 8);
    const std::uint32_t cls = U32(flags) & 0xff;
    const bool complex = (U32(flags) & kComplexFlag) != 0;
    // Dimensions.
    t = Sub(src, avail, where, "the dimensions");
    if (t.type != kMiInt32 || t.bytes % 4 != 0) Fail(where, "no dimensions where they belong");
    std::vector<std::uint64_t> dims;
    std::uint64_t rank = 0;
    double declared = 1;
    bool negative = false;
    ForEachWord(src, t, avail, where, [&](std::uint32_t w) {
      if (w & 0x80000000u) negative = true;
      if (++rank <= 32) dims.push_back(w);
      declared = std::min(declared * static_cast<double>(w), kElementCountCap);
    });
    // Name (empty inside cells and structs).
    t = Sub(src, avail, where, "the name");
    if (t.type != kMiInt8) Fail(where, "no name where it belongs");
    // matio allocates the whole name element; a NUL-padded one could be hundreds of megabytes.
    if (t.bytes > kMaxNameBytes)
      Fail(where, fmt::format("a name element of {} bytes, more than the {} a name may take",
                              t.bytes, kMaxNameBytes));
    std::string name(static_cast<std::size_t>(std::min<std::uint64_t>(t.bytes, 256)), '\0');
    Content(src, t, avail, where, reinterpret_cast<unsigned char*>(name.data()), name.size());
    name = name.substr(0, name.find('\0'));
    if (top) {
      where = path_ + ":" + Printable(name);
      prefix_.clear();
      current_ = where;
    }
    if (rank == 0) Fail(where, "an array without dimensions");
    // A negative size is left to the reader's own refusal (matio: "Integer multiplication
    // overflow"); nothing below is sized by it.
    if (negative) return Discard(src, avail, where);
    const std::string shape = rank <= 32 ? FormatDims(dims) : fmt::format("{}-D", rank);
    if (cls >= kFirstNumeric && cls <= kLastNumeric) {
      Values(src, avail, where, shape, declared, false, false);
      if (complex) Values(src, avail, where, shape, declared, true, false);
    } else if (cls == kChar) {
      Values(src, avail, where, shape, declared, false, true);
    } else if (cls == kCell) {
      Children(src, avail, where, shape, declared, {}, depth);
    } else if (cls == kStruct || cls == kObject) {
      if (cls == kObject) SkipSub(src, avail, where, "the class name");
      unsigned char len_bytes[4] = {};
      t = Sub(src, avail, where, "the field name length");
      if (t.type != kMiInt32 || t.bytes != 4) Fail(where, "no field name length where it belongs");
      Content(src, t, avail, where, len_bytes, 4);
      const std::uint32_t len = U32(len_bytes);
      if (len > kMaxNameBytes)
        Fail(where, fmt::format("field names of {} bytes each, more than the {} a name may take",
                                len, kMaxNameBytes));
      t = Sub(src, avail, where, "the field names");
      if (t.type != kMiInt8 || (len == 0 ? t.bytes != 0 : t.bytes % len != 0))
        Fail(where, "field names that do not fit their length");
      std::vector<std::string> fields;
      if (len != 0) {
        const std::uint64_t n = t.bytes / len;
        budget_.Reserve(static_cast<double>(n), where);
        std::string all(static_cast<std::size_t>(std::min<std::uint64_t>(t.bytes, 1u << 20)), '\0');
        Content(src, t, avail, where, reinterpret_cast<unsigned char*>(all.data()), all.size());
        for (std::uint64_t i = 0; i < n; ++i) {
          const std::uint64_t at = i * len;
          std::string f = at < all.size() ? all.substr(static_cast<std::size_t>(at), len) : "";
          fields.push_back(f.substr(0, f.find('\0')));
        }
      } else {
        Content(src, t, avail, where, nullptr, 0);
      }
      if (!fields.empty()) Children(src, avail, where, shape, declared, fields, depth);
    }
    // Sparse, function and opaque classes: not read as values by the reader (sparse is refused
    // by name); their bytes are only bounded by the element.
    Discard(src, avail, where);
  }

 private:
  // The next sub-element's tag; its content is left for Content/SkipSub.
  Tag Sub(ByteSource& src, std::uint64_t& avail, const std::string& where, const char* what) {
    if (avail < 8) Fail(where, fmt::format("{} missing (the variable's element ends)", what));
    unsigned char b[8];
    if (!src.Read(b, 8)) Fail(where, fmt::format("{} cut off ({})", what, src.Problem()));
    avail -= 8;
    Tag t;
    const std::uint32_t w0 = U32(b);
    if ((w0 >> 16) != 0) {
      t.is_small = true;
      t.type = w0 & 0xffff;
      t.bytes = w0 >> 16;
      if (t.bytes > 4) Fail(where, fmt::format("{}: a small element of {} bytes", what, t.bytes));
      std::copy(b + 4, b + 8, t.small);
      return t;
    }
    t.type = w0;
    t.bytes = U32(b + 4);
    if (t.bytes > avail)
      Fail(where, fmt::format("{}: {} bytes declared, {} left in the variable's element", what,
                              t.bytes, avail));
    return t;
  }

  // Reads up to `n` bytes of `t`'s content into `out`, skips the rest and the padding to 8.
  void Content(ByteSource& src, const Tag& t, std::uint64_t& avail, const std::string& where,
               unsigned char* out, std::size_t n) {
    const std::size_t k = static_cast<std::size_t>(std::min<std::uint64_t>(n, t.bytes));
    if (t.is_small) {
      std::copy(t.small, t.small + k, out);
      return;
    }
    if (k > 0 && !src.Read(out, k)) Fail(where, "data cut off (" + src.Problem() + ")");
    const std::uint64_t padded = Padded(t.bytes, avail);
    avail -= k;
    SkipBytes(src, padded - k, avail, where);
  }

  void SkipSub(ByteSource& src, std::uint64_t& avail, const std::string& where, const char* what) {
    const Tag t = Sub(src, avail, where, what);
    if (!t.is_small) SkipBytes(src, Padded(t.bytes, avail), avail, where);
  }

  // A content's size with its padding to 8 bytes, as far as the element still has bytes (the
  // padding of an element's last sub-element may be left out).
  static std::uint64_t Padded(std::uint64_t bytes, std::uint64_t avail) {
    return std::min<std::uint64_t>(avail, bytes + (8 - bytes % 8) % 8);
  }

  void SkipBytes(ByteSource& src, std::uint64_t n, std::uint64_t& avail, const std::string& where) {
    if (n > avail) Fail(where, "data past the variable's element");
    if (n > 0 && !src.Skip(n)) Fail(where, "data cut off (" + src.Problem() + ")");
    avail -= n;
  }

  void Discard(ByteSource& src, std::uint64_t& avail, const std::string& where) {
    SkipBytes(src, avail, avail, where);
  }

  template <typename F>
  void ForEachWord(ByteSource& src, const Tag& t, std::uint64_t& avail, const std::string& where,
                   F&& f) {
    if (t.is_small) {
      for (std::uint64_t i = 0; i + 4 <= t.bytes; i += 4) f(U32(t.small + i));
      return;
    }
    unsigned char w[4];
    for (std::uint64_t i = 0; i + 4 <= t.bytes; i += 4) {
      if (!src.Read(w, 4)) Fail(where, "dimensions cut off (" + src.Problem() + ")");
      f(U32(w));
    }
    const std::uint64_t padded = Padded(t.bytes, avail);
    avail -= t.bytes;
    SkipBytes(src, padded - t.bytes, avail, where);
  }

  // A numeric (or char) array's values: the data element's byte count over its type's size must
  // equal the product of the dims. Past kMaxVariableElements the reader refuses the variable by
  // its declaration before reading (with its own message), so the count is not compared there.
  void Values(ByteSource& src, std::uint64_t& avail, const std::string& where,
              const std::string& shape, double declared, bool imaginary, bool is_char) {
    const char* part = imaginary ? "imaginary part: " : "";
    if (avail == 0 && declared == 0) return;  // an empty array may omit its data element
    const Tag t = Sub(src, avail, where, imaginary ? "the imaginary part" : "the values");
    const std::uint64_t size = NumericSize(t.type);
    // Characters may be stored as UTF-8/16/32 (16, 17, 18), whose byte counts are not per char.
    const bool text = is_char && (t.type == kMiUtf16 || t.type == 16 || t.type == 18);
    if (size == 0 && !text)
      Fail(where,
           fmt::format("{}values stored as MAT data type {}, not a number type", part, t.type));
    if (size != 0 && declared <= kMaxVariableElements) {
      const std::uint64_t holds = t.bytes / size;
      if (static_cast<double>(holds) != declared || t.bytes % size != 0)
        Fail(where,
             fmt::format(
                 "{}declares {} ({:.0f} elements), holds {}{}", part, shape, declared, holds,
                 t.bytes % size != 0 ? fmt::format(" and {} stray bytes", t.bytes % size) : ""));
    }
    if (!t.is_small) SkipBytes(src, Padded(t.bytes, avail), avail, where);
  }

  // A cell's elements or a struct's fields (`fields` empty for a cell): one miMATRIX each,
  // element by element, field by field.
  void Children(ByteSource& src, std::uint64_t& avail, const std::string& where,
                const std::string& shape, double declared, const std::vector<std::string>& fields,
                int depth) {
    const std::uint64_t per = fields.empty() ? 1 : fields.size();
    // Before the first element: matio allocates every one it is told of.
    budget_.Reserve(declared * static_cast<double>(per), where);
    const std::uint64_t n = static_cast<std::uint64_t>(declared);
    for (std::uint64_t i = 0; i < n; ++i)
      for (std::uint64_t f = 0; f < per; ++f) {
        std::string child =
            fields.empty()
                ? fmt::format("{}{{{}}}", where, i + 1)
                : fmt::format("{}{}.{}", where, n > 1 ? fmt::format("({})", i + 1) : "", fields[f]);
        if (avail < 8)
          Fail(where, fmt::format("declares {} ({:.0f} {}), holds {}", shape, declared,
                                  fields.empty() ? "cells" : "struct elements", i));
        const Tag t = Sub(src, avail, where, "an element");
        if (t.type != kMiMatrix || t.is_small)
          Fail(child, fmt::format("an element of MAT data type {}, expected a matrix", t.type));
        avail -= t.bytes;
        Matrix(src, t.bytes, child, false, depth + 1);
      }
  }

  std::string path_;
  bool little_;
  std::string prefix_;
  std::string current_;
  WalkBudget budget_;
};

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

}  // namespace

namespace {

// A MAT v7.3 file is HDF5 behind a 512-byte MAT header. matio opens it without complaint even
// when HDF5 cannot (a truncated file: HDF5 checks the superblock's end-of-file address against
// the file's size) and then lists no variables, exit 0: so HDF5 opens it here first, walks it
// as matio will under the container policy (no value outside the file, no cycle, bounded), and
// counts the root's variables as matio lists them, for the caller to compare.
std::size_t CheckMat73(const std::string& path) {
  SilenceHdf5Errors();
  const Hdf5Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!file.ok())
    throw InputError(path +
                     ": malformed or truncated MAT file: a MAT v7.3 file that HDF5 "
                     "cannot open (truncated, or no HDF5 data after the 512-byte MAT "
                     "header)");
  return WalkHdf5(file.get(), path, Hdf5Walk::kMat73).root_variables;
}

// A MAT v4 file: matrices one after the other, each a 20-byte header (type MOPT, rows, columns,
// imaginary flag, name length: int32s in the byte order the type's M digit names), the name,
// then rows x columns values (twice with the imaginary flag). matio allocates the name length
// and the data a header declares before reading them: a 54-byte file declaring a name of
// 0x7fffffff bytes made it allocate 2.1 GB (refused only after that, by the short read). Every
// header is compared with the bytes the file has left first.
std::size_t CheckMat4(const std::string& path, std::FILE* f, std::uint64_t size) {
  std::size_t variables = 0;
  std::uint64_t pos = 0;
  WalkBudget budget;
  const auto fail = [&](const std::string& where, const std::string& detail) {
    throw InputError(where + ": malformed or truncated MAT file: " + detail);
  };
  while (pos < size) {
    const std::string at = fmt::format("at byte {}: ", pos);
    unsigned char h[20];
    if (size - pos < 20)
      fail(path,
           at + fmt::format("{} stray bytes where a MAT v4 header (20 bytes) belongs", size - pos));
    if (fseeko(f, static_cast<off_t>(pos), SEEK_SET) != 0 || std::fread(h, 1, 20, f) != 20)
      fail(path, at + "cannot read the file");
    const auto word = [&](int i, bool little) {
      const unsigned char* b = h + 4 * i;
      return static_cast<std::int32_t>(
          little ? (std::uint32_t{b[0]} | std::uint32_t{b[1]} << 8 | std::uint32_t{b[2]} << 16 |
                    std::uint32_t{b[3]} << 24)
                 : (std::uint32_t{b[3]} | std::uint32_t{b[2]} << 8 | std::uint32_t{b[1]} << 16 |
                    std::uint32_t{b[0]} << 24));
    };
    // The byte order: the one in which the type is a valid MOPT (at most 4052), as matio tries.
    bool little = true;
    if (word(0, true) < 0 || word(0, true) > 4052) little = false;
    const std::int32_t type = word(0, little);
    if (type < 0 || type > 4052)
      fail(path, at + "not a MAT v4 header (its type is no MOPT code in either byte order)");
    static constexpr int kSize[] = {8, 4, 4, 2, 2, 1};  // P: double, single, int32, int16, ...
    const int p = (type / 10) % 10;
    if ((type / 100) % 10 != 0 || p > 5 || type % 10 > 2)
      fail(path, at + fmt::format("MAT v4 type {} is not a known MOPT code", type));
    const std::int32_t rows = word(1, little), cols = word(2, little), imag = word(3, little),
                       namelen = word(4, little);
    if (rows < 0 || cols < 0 || namelen < 0)
      fail(path, at + fmt::format("a MAT v4 header declaring {} rows, {} columns, a {}-byte name",
                                  rows, cols, namelen));
    std::uint64_t left = size - pos - 20;
    if (static_cast<std::uint64_t>(namelen) > left)
      fail(path, at + fmt::format("a MAT v4 variable with a {}-byte name, the file has {} bytes "
                                  "left",
                                  namelen, left));
    std::string name(static_cast<std::size_t>(std::min(namelen, 256)), '\0');
    if (!name.empty() && std::fread(name.data(), 1, name.size(), f) != name.size())
      fail(path, at + "cannot read the file");
    name = name.substr(0, name.find('\0'));
    left -= static_cast<std::uint64_t>(namelen);
    // In double: rows x cols x 8 x 2 may pass 2^64; the comparison only needs to be exact
    // below the file's size.
    const double declared = static_cast<double>(rows) * static_cast<double>(cols);
    const double bytes = declared * kSize[p] * (imag != 0 ? 2 : 1);
    if (bytes > static_cast<double>(left))
      fail(path + ":" + name,
           fmt::format("declares {}x{} ({:.0f} elements, {:.0f} bytes), the file has {} bytes "
                       "left",
                       rows, cols, declared, bytes, left));
    budget.Count(path + ":" + Printable(name));
    ++variables;
    pos = size - left + static_cast<std::uint64_t>(bytes);
  }
  return variables;
}

}  // namespace

std::optional<std::size_t> CheckMatLayout(const std::string& path) {
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
  if (!file) return std::nullopt;  // matio reports why it cannot open it
  std::FILE* f = file.get();
  if (fseeko(f, 0, SEEK_END) != 0) return std::nullopt;
  const std::uint64_t size = static_cast<std::uint64_t>(ftello(f));
  unsigned char header[128];
  const bool magic =
      size >= 128 && fseeko(f, 0, SEEK_SET) == 0 &&
      std::fread(header, 1, sizeof header, f) == sizeof header &&
      ((header[126] == 'I' && header[127] == 'M') || (header[126] == 'M' && header[127] == 'I'));
  const bool little = magic && header[126] == 'I';
  const unsigned version = !magic   ? 0
                           : little ? header[124] | (header[125] << 8u)
                                    : header[125] | (header[124] << 8u);
  if (version == 0x0200) {
    file.reset();
    return CheckMat73(path);
  }
  // Neither v5 nor v7.3: matio tries MAT v4, which has no magic.
  if (version != 0x0100) return CheckMat4(path, f, size);
  LayoutChecker check(path, little);
  std::size_t variables = 0;
  std::uint64_t pos = 128;
  std::uint64_t inflated = 0;
  while (pos < size) {
    check.SetPrefix(fmt::format("at byte {}: ", pos));
    unsigned char tag[8];
    // A cut file, or bytes after the last variable: matio stops there (with a warning when it
    // notices), so the variables it lists would not be all the file was meant to hold.
    if (size - pos < 8)
      check.Fail(path, fmt::format("{} stray bytes where a variable's tag belongs", size - pos));
    if (fseeko(f, static_cast<off_t>(pos), SEEK_SET) != 0 || std::fread(tag, 1, 8, f) != 8)
      check.Fail(path, "cannot read the file");
    const std::uint32_t type = check.U32(tag);
    const std::uint64_t bytes = check.U32(tag + 4);
    // Only matrices (plain or compressed) belong at the top level of a MAT v5 file; matio stops
    // at anything else, silently for some (it lists 200 bytes of 0xFF after a valid header as a
    // file of 0 variables).
    if (type != kMiMatrix && type != kMiCompressed)
      check.Fail(path, fmt::format("an element of MAT data type {} where a variable belongs "
                                   "(garbage, or a damaged file)",
                                   type));
    if (bytes > size - pos - 8)
      check.Fail(
          path, fmt::format("a variable of {} bytes, the file has {} left", bytes, size - pos - 8));
    if (type == kMiMatrix) {
      FileSpan span(f);
      check.Matrix(span, bytes, path, true, 0);
    } else {
      InflatedSpan span(f, bytes, &inflated);
      try {
        unsigned char inner[8];
        if (!span.Read(inner, 8))
          check.Fail(path, "a compressed variable without its matrix (" + span.Problem() + ")");
        if (check.U32(inner) != kMiMatrix)
          check.Fail(path, fmt::format("a compressed element of MAT data type {}, expected a "
                                       "matrix",
                                       check.U32(inner)));
        check.Matrix(span, check.U32(inner + 4), path, true, 0);
      } catch (const InflateBound& bound) {
        // Refused, not skipped: an unchecked variable is one matio may misread.
        if (bound.whole_file)
          throw InputError(fmt::format(
              "{}: refused: its compressed variables inflate past {} bytes in all, the bound on "
              "one file (docs/robustness.md, \"Files from elsewhere\")",
              path, kMaxInflatedFileBytes));
        throw InputError(fmt::format(
            "{}: refused: a compressed variable inflating past {} bytes, the bound on one "
            "variable (docs/robustness.md, \"Files from elsewhere\")",
            check.current(), kMaxInflatedVariableBytes));
      }
    }
    ++variables;  // an empty miMATRIX too: matio lists it (without a name)
    pos += 8 + bytes;
  }
  return variables;
}

}  // namespace sysid::internal
