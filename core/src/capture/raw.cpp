// RAW decoding with LibRaw: the only file that includes libraw.h.
#include "tristim/capture/raw.hpp"

#include <libraw/libraw.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <memory>
#include <new>
#include <sstream>

#include "tristim/colorimetry/colorimetry.hpp"
#include "tristim/error.hpp"
#include "tristim/io/fields.hpp"
#include "../large_buffer.hpp"
#include "percentile.hpp"
#include "../simd4.hpp"

namespace tristim {

namespace {

/// The one place where LibRaw's return codes become tristim errors.
void check_libraw(int rc, const char* step) {
  if (rc == LIBRAW_SUCCESS) return;
  const std::string what = std::string("LibRaw ") + step + ": " + libraw_strerror(rc);
  switch (rc) {
    case LIBRAW_FILE_UNSUPPORTED:
    case LIBRAW_REQUEST_FOR_NONEXISTENT_IMAGE:
    case LIBRAW_NOT_IMPLEMENTED:
      throw Error(ErrorCode::RawUnsupported, "not a RAW file this decoder supports (" + what + ")");
    case LIBRAW_IO_ERROR:
      throw Error(ErrorCode::RawTruncated, "the RAW data ends early or cannot be read (" + what + ")");
    case LIBRAW_DATA_ERROR:
    case LIBRAW_BAD_CROP:
    case LIBRAW_UNSPECIFIED_ERROR:
      throw Error(ErrorCode::RawCorrupt, "the RAW data is corrupt (" + what + ")");
    case LIBRAW_UNSUFFICIENT_MEMORY:
    case LIBRAW_TOO_BIG:
    case LIBRAW_MEMPOOL_OVERFLOW:
      throw Error(ErrorCode::RawTooLarge, "the RAW image needs too much memory (" + what + ")");
    default:
      throw Error(ErrorCode::Internal, what);
  }
}

int channel_of_letter(char c) {
  switch (c) {
    case 'R': return 0;
    case 'G': return 1;
    case 'B': return 2;
    default: return -1;
  }
}

std::string format_timestamp(std::int64_t t) {
  if (t <= 0) return "";
  // LibRaw built the time_t from the camera's local clock with mktime(); localtime() undoes it
  // whatever the machine's zone, giving the camera clock back.
  std::time_t tt = static_cast<std::time_t>(t);
  std::tm tmv{};
#if defined(_WIN32)
  localtime_s(&tmv, &tt);
#else
  localtime_r(&tt, &tmv);
#endif
  char buf[64];
  std::snprintf(buf, sizeof buf, "%04d-%02d-%02dT%02d:%02d:%02d", tmv.tm_year + 1900,
                tmv.tm_mon + 1, tmv.tm_mday, tmv.tm_hour, tmv.tm_min, tmv.tm_sec);
  return buf;
}

/// A LibRaw object is large (about 0.75 MB, plus 0.28 MB of tables it allocates itself), and
/// identify() and unpack() write most of it. Fresh memory costs a page fault per 4 KB: a few ms per
/// file on some VMs, and most of the RAW fuzzer's time under AddressSanitizer, which maps every
/// large allocation anew. So each thread keeps the storage of its last LibRaw and constructs the
/// next one in it. The object is still constructed and destroyed as usual, on storage zeroed
/// first (as fresh pages are: LibRaw leaves some members, e.g. its IFD table, to identify()), so
/// nothing carries over from one file to the next.
class LibRawStorage {
 public:
  ~LibRawStorage() { ::operator delete(block_); }
  void* acquire() {
    if (busy_) return nullptr;  // a second LibRaw alive on this thread: it gets fresh memory
    if (block_ == nullptr) block_ = ::operator new(sizeof(LibRaw));
    std::memset(block_, 0, sizeof(LibRaw));
    busy_ = true;
    return block_;
  }
  bool owns(const void* p) const { return p == block_ && busy_; }
  void release() { busy_ = false; }

 private:
  void* block_ = nullptr;
  bool busy_ = false;
};

thread_local LibRawStorage libraw_storage;

struct LibRawDelete {
  void operator()(LibRaw* p) const {
    if (libraw_storage.owns(p)) {
      p->~LibRaw();
      libraw_storage.release();
    } else {
      delete p;
    }
  }
};
using LibRawPtr = std::unique_ptr<LibRaw, LibRawDelete>;

LibRawPtr make_libraw() {
  LibRawPtr p;
  if (void* block = libraw_storage.acquire()) {
    try {
      p = LibRawPtr(new (block) LibRaw(LIBRAW_OPTIONS_NONE));
    } catch (...) {
      libraw_storage.release();
      throw;
    }
  } else {
    p = LibRawPtr(new LibRaw(LIBRAW_OPTIONS_NONE));
  }
  // LibRaw's default handlers print data and memory errors to stderr (the console, in the page);
  // its return codes and error_count() say the same, and become coded errors (open_and_unpack).
  p->set_dataerror_handler([](void*, const char*, const int) {}, nullptr);
  p->set_memerror_handler([](void*, const char*, const char*) {}, nullptr);
  return p;
}

/// LibRaw's memory stream with gets() and scanf_one() that stay inside their buffers. LibRaw
/// 0.20.2's LibRaw_buffer_datastream::gets copies up to `sz` bytes with no terminating zero when a
/// line fills the buffer, and writes the zero one byte past it when the file ends `sz` − 1 bytes
/// later; its scanf_one runs sscanf on the file bytes, which are not zero-terminated (a read past
/// the end of the file's buffer). fuzz_raw found the first as a stack-buffer-overflow in
/// parse_rollei's 128-byte line (tests/fuzz/corpus/raw/crash-f5c9985c…); LibRaw reads every text
/// field (Make, Model, Software, Rollei/Leaf text headers) through these two. Here: fgets's
/// contract (at most sz − 1 bytes, up to and including a newline, then a zero) and sscanf on a
/// bounded, zero-terminated copy; everything else is LibRaw's own stream.
class BoundedBufferStream final : public LibRaw_buffer_datastream {
 public:
  BoundedBufferStream(const std::uint8_t* data, std::size_t size)
      : LibRaw_buffer_datastream(const_cast<std::uint8_t*>(data), size), data_(data), size_(size) {}

  char* gets(char* s, int sz) override {
    const INT64 at = tell();
    if (sz < 1 || at < 0 || static_cast<std::size_t>(at) >= size_) return nullptr;
    std::size_t p = static_cast<std::size_t>(at);
    int k = 0;
    while (p < size_ && k < sz - 1) {
      const char c = static_cast<char>(data_[p++]);
      s[k++] = c;
      if (c == '\n') break;
    }
    s[k] = 0;
    seek(static_cast<INT64>(p), SEEK_SET);
    return s;
  }

  int scanf_one(const char* fmt, void* val) override {
    const INT64 at = tell();
    if (at < 0 || static_cast<std::size_t>(at) > size_) return 0;
    const std::size_t pos = static_cast<std::size_t>(at);
    // LibRaw asks for one number ("%d", "%f"): 63 bytes hold any white space before it that
    // matters and the number itself (its own loop below skips at most 25 bytes).
    char text[64];
    const std::size_t n = std::min(sizeof text - 1, size_ - pos);
    std::memcpy(text, data_ + pos, n);
    text[n] = 0;
    const int res = std::sscanf(text, fmt, val);
    if (res > 0) {  // LibRaw's advance: to the next zero, blank, tab or newline, at most 25 bytes
      std::size_t p = pos;
      for (int count = 1; p < size_; ++count) {
        ++p;
        if (p >= size_) break;
        const std::uint8_t c = data_[p];
        if (c == 0 || c == ' ' || c == '\t' || c == '\n' || count > 24) break;
      }
      seek(static_cast<INT64>(p), SEEK_SET);
    }
    return res;
  }

  // LibRaw's parsers loop on file-given sizes; its seek clamps at the end, so a loop that only
  // checks the position against a claimed end never ends (parse_riff's "nctg" chunk: an 85-byte
  // file hung tristim, fuzz_raw). While LibRaw identifies the file, reads that find no byte left
  // are counted, and past a budget no real header needs the open fails as corrupt data.
  int read(void* ptr, size_t sz, size_t nmemb) override {
    const int got = LibRaw_buffer_datastream::read(ptr, sz, nmemb);
    if (got == 0 && identifying_ && sz * nmemb > 0 && --eof_reads_left_ < 0) throw LIBRAW_EXCEPTION_IO_CORRUPT;
    return got;
  }
  /// The open is done: decoders count damaged data themselves (error_count, RAW_TRUNCATED).
  void identified() { identifying_ = false; }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  bool identifying_ = true;
  long eof_reads_left_ = 1L << 16;
};

/// LibRaw::open_buffer with the stream above; LibRaw owns (and deletes) the stream once the open
/// succeeded, as open_buffer arranges for its own.
int open_memory(LibRaw& proc, const std::uint8_t* data, std::size_t size) {
  if (data == nullptr) return LIBRAW_IO_ERROR;
  auto stream = std::make_unique<BoundedBufferStream>(data, size);
  auto& internal = proc.get_internal_data_pointer()->internal_data;
  internal.input_internal = 0;  // not deleted by LibRaw if the open fails
  const int rc = proc.open_datastream(stream.get());
  stream->identified();
  if (rc == LIBRAW_SUCCESS) {
    stream.release();
    internal.input_internal = 1;  // deleted by LibRaw's recycle()
  }
  return rc;
}

/// Opens the buffer (and unpacks when `unpack`), with our size limits. The buffer must outlive
/// the returned processor until unpack is done.
LibRawPtr open_and_unpack(const std::uint8_t* data, std::size_t size,
                                        const DecodeOptions& options, bool unpack) {
  if (size == 0 || data == nullptr) throw Error(ErrorCode::EmptyFile, "the RAW file is empty (0 bytes)");
  if (size < 64)
    throw Error(ErrorCode::RawUnsupported,
                "the file is only " + std::to_string(size) + " bytes: not a RAW file");
  LibRawPtr proc = make_libraw();
  // LibRaw's own allocation limit, aligned with ours (bytes of the raw raster, MB).
  // (8 bytes per pixel covers 4-channel linear DNGs; Bayer rasters need 2.)
  proc->imgdata.params.max_raw_memory_mb =
      static_cast<unsigned>(std::min(2048.0, std::max(64.0, options.max_megapixels * 8.0)));
  check_libraw(open_memory(*proc, data, size), "open_buffer");

  const auto& S = proc->imgdata.sizes;
  const double mp = static_cast<double>(S.raw_width) * S.raw_height / 1e6;
  if (S.raw_width == 0 || S.raw_height == 0 || S.width == 0 || S.height == 0)
    throw Error(ErrorCode::RawCorrupt, "the RAW header gives zero image dimensions");
  if (mp > options.max_megapixels) {
    std::ostringstream ss;
    ss << "the RAW header claims " << S.raw_width << " x " << S.raw_height << " pixels ("
       << mp << " MP), over the limit of " << options.max_megapixels << " MP";
    throw Error(ErrorCode::RawTooLarge, ss.str());
  }
  if (S.top_margin + S.height > S.raw_height || S.left_margin + S.width > S.raw_width)
    throw Error(ErrorCode::RawCorrupt, "the RAW header's visible area lies outside its raster");

  // Uncompressed 16-bit data must fit in the file: catch truncation before LibRaw reads zeros.
  libraw_decoder_info_t info{};
  proc->get_decoder_info(&info);
  const auto& U = proc->get_internal_data_pointer()->unpacker_data;
  const INT64 off = U.data_offset;
  if (off > 0 && static_cast<std::size_t>(off) >= size)
    throw Error(ErrorCode::RawTruncated, "the RAW image data would start at byte " +
                                             std::to_string(off) + ", past the end of the " +
                                             std::to_string(size) + "-byte file");
  if (U.data_size > 0 && off > 0 && static_cast<std::size_t>(off + U.data_size) > size)
    throw Error(ErrorCode::RawTruncated, "the RAW image data needs bytes " + std::to_string(off) +
                                             ".." + std::to_string(off + U.data_size) +
                                             " but the file has " + std::to_string(size));
  // Kodak RADC (DC40/DC50, always 768 x 512) decodes two columns per step from width / 2 down;
  // a width that is not a multiple of 4 can step to column -1, and LibRaw's run-length branch
  // then adds into index -1 of its row buffer (kodak_decoders.cpp:121, UBSan "index -1 out of
  // bounds"; it stays inside the 3-D stack array, so no memory error, but the image is garbage).
  // Found by fuzz_raw: tests/fuzz/corpus/raw/crash-012db9de…
  if (info.decoder_name && std::strcmp(info.decoder_name, "kodak_radc_load_raw()") == 0 &&
      S.width % 4 != 0)
    throw Error(ErrorCode::RawCorrupt, "the Kodak RADC header gives an image width of " +
                                           std::to_string(S.width) +
                                           "; its decoder needs a multiple of 4 (768 in every camera that writes it)");
  if (unpack) {
    check_libraw(proc->unpack(), "unpack");
    const int errors = proc->error_count();
    if (errors > 0 && proc->get_internal_data_pointer()->internal_data.input->eof())
      throw Error(ErrorCode::RawTruncated, "the RAW image data ends before the image is complete");
    // LibRaw counts undecodable data (an invalid compressed code, a bad block) and carries on
    // with whatever values it got; measurements from such an image would be silently wrong.
    if (errors > 0)
      throw Error(ErrorCode::RawCorrupt, "the RAW image data is damaged: LibRaw's decoder met " +
                                             std::to_string(errors) + " undecodable part" +
                                             (errors == 1 ? "" : "s") + " (" + info.decoder_name + ")");
  }
  return proc;
}

struct LayoutInfo {
  std::string layout;
  int block = 1;
  int period = 1;                 // CFA repeat of the channel map (2 Bayer, 6 X-Trans)
  std::vector<int> channel;       // period*period: 0/1/2 channel of each CFA position
  std::string pattern;
  int cfa_w = 0, cfa_h = 0;
};

LayoutInfo classify(LibRaw& p) {
  const auto& I = p.imgdata.idata;
  const auto& R = p.imgdata.rawdata;
  LayoutInfo L;
  if (I.is_foveon) throw Error(ErrorCode::RawUnsupported, "Foveon (layered) sensors are not supported");
  if (R.float_image || R.float3_image || R.float4_image)
    throw Error(ErrorCode::RawUnsupported, "floating-point RAW data is not supported");
  if (p.get_internal_data_pointer()->internal_output_params.fuji_width)
    throw Error(ErrorCode::RawUnsupported,
                "Fujifilm SuperCCD (45-degree rotated) layouts are not supported");
  const std::string cdesc(I.cdesc);
  if (I.filters == 0) {
    if (R.raw_image && I.colors == 1) {
      L.layout = "monochrome";
    } else if ((R.color3_image || R.color4_image) && I.colors == 3) {
      L.layout = "linear";
    } else {
      throw Error(ErrorCode::RawUnsupported, "non-CFA RAW with " + std::to_string(I.colors) +
                                                 " colours (" + cdesc + ") is not supported");
    }
    return L;
  }
  if (!R.raw_image)
    throw Error(ErrorCode::RawUnsupported, "CFA data without a single-channel raster is not supported");
  if (I.filters == 9) {  // X-Trans 6x6
    L.layout = "xtrans";
    L.block = 3;
    L.period = 6;
    L.cfa_w = L.cfa_h = 6;
  } else if (I.filters >= 1000) {
    // A true 2x2 Bayer-like pattern repeats every 2 rows in the 8-row filters word.
    if (I.filters != (I.filters & 0xff) * 0x01010101u)
      throw Error(ErrorCode::RawUnsupported, "CFA pattern larger than 2x2 (filters 0x" +
                                                 hash_hex(I.filters) + ") is not supported");
    L.layout = "bayer";
    L.block = 2;
    L.period = 2;
    L.cfa_w = L.cfa_h = 2;
  } else {
    throw Error(ErrorCode::RawUnsupported,
                "unusual CFA layout (LibRaw filters = " + std::to_string(I.filters) + ") is not supported");
  }
  L.channel.resize(static_cast<size_t>(L.period) * L.period);
  for (int r = 0; r < L.period; ++r)
    for (int c = 0; c < L.period; ++c) {
      const int k = p.COLOR(r, c);
      const char letter = (k >= 0 && k < 4) ? cdesc[k] : '?';
      const int ch = channel_of_letter(letter);
      if (ch < 0)
        throw Error(ErrorCode::RawUnsupported, std::string("CFA colour '") + letter +
                                                   "' (colours " + cdesc +
                                                   ") is not R, G or B: 4-colour sensors are not supported");
      L.channel[r * L.period + c] = ch;
      L.pattern += letter;
    }
  // Every block must see R, G and B.
  for (int by = 0; by < L.period; by += L.block)
    for (int bx = 0; bx < L.period; bx += L.block) {
      int seen = 0;
      for (int r = 0; r < L.block; ++r)
        for (int c = 0; c < L.block; ++c) seen |= 1 << L.channel[(by + r) * L.period + bx + c];
      if (seen != 7)
        throw Error(ErrorCode::RawUnsupported,
                    "CFA pattern " + L.pattern + " has a block without R, G and B");
    }
  return L;
}

void fill_metadata(LibRaw& p, const LayoutInfo& L, RawMetadata& m) {
  const auto& I = p.imgdata.idata;
  const auto& S = p.imgdata.sizes;
  const auto& C = p.imgdata.color;
  const auto& O = p.imgdata.other;
  m.make = I.make;
  m.model = I.model;
  m.lens = p.imgdata.lens.Lens;
  if (m.lens.empty()) m.lens = p.imgdata.lens.makernotes.Lens;
  m.iso = O.iso_speed;
  m.shutter_s = O.shutter;
  m.f_number = O.aperture;
  m.timestamp = static_cast<std::int64_t>(O.timestamp);
  m.timestamp_iso = format_timestamp(m.timestamp);
  m.layout = L.layout;
  m.cfa_pattern = L.pattern;
  m.cfa_width = L.cfa_w;
  m.cfa_height = L.cfa_h;
  m.block = L.block;
  m.sensor_width = S.width;
  m.sensor_height = S.height;
  m.raw_width = S.raw_width;
  m.raw_height = S.raw_height;
  m.width = S.width / L.block;
  m.height = S.height / L.block;
  m.bits = static_cast<int>(C.raw_bps);
  m.flip = S.flip;
  m.white_level = C.maximum;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      m.rgb_cam[i * 3 + j] = C.rgb_cam[i][j];
      m.cam_xyz[i * 3 + j] = C.cam_xyz[i][j];
    }
  // DNG files keep their ColorMatrix in dng_color (cam_xyz stays zero): prefer D65 (21).
  bool have_cam_xyz = false;
  for (double v : m.cam_xyz) have_cam_xyz = have_cam_xyz || v != 0;
  if (!have_cam_xyz) {
    int k = C.dng_color[1].illuminant == 21 ? 1 : 0;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) m.cam_xyz[i * 3 + j] = C.dng_color[k].colormatrix[i][j];
  }
  const auto norm = [](const float* mul, std::array<double, 3>& out) {
    const double g = mul[1] > 0 ? mul[1] : 1.0;
    for (int c = 0; c < 3; ++c) out[c] = mul[c] > 0 ? mul[c] / g : 1.0;
  };
  norm(C.cam_mul, m.as_shot_wb);
  norm(C.pre_mul, m.daylight_wb);
  m.decoder = p.unpack_function_name();
}

/// Black level of the sensor pixel at visible (row, col): black + per-colour + repeat pattern.
struct BlackModel {
  double base = 0;
  double per_colour[4] = {0, 0, 0, 0};
  int rep_h = 0, rep_w = 0;
  std::vector<double> rep;
  double at(int row, int col, int colour_index) const {
    double b = base + per_colour[colour_index & 3];
    if (rep_h > 0 && rep_w > 0) b += rep[(row % rep_h) * rep_w + col % rep_w];
    return b;
  }
};

BlackModel black_model(LibRaw& p) {
  const auto& C = p.imgdata.color;
  BlackModel b;
  b.base = C.black;
  for (int i = 0; i < 4; ++i) b.per_colour[i] = C.cblack[i];
  if (C.cblack[4] > 0 && C.cblack[5] > 0 && C.cblack[4] * C.cblack[5] <= LIBRAW_CBLACK_SIZE - 6) {
    b.rep_h = static_cast<int>(C.cblack[4]);
    b.rep_w = static_cast<int>(C.cblack[5]);
    for (int i = 0; i < b.rep_h * b.rep_w; ++i) b.rep.push_back(C.cblack[6 + i]);
  }
  return b;
}

#ifdef TRISTIM_SIMD4
/// The Bayer fast path of build_image, 4 output pixels per step (SSE2 natively, SIMD128 in wasm):
/// the same floats as its scalar loop. Each 2×2 block's values minus their black are summed per
/// channel in block order k = 0..3 (the values of other channels masked to +0, which leaves every
/// sum as the scalar loop's) and scaled by 1/count; a channel's saturation bit is set when one of
/// its values reaches its threshold. Returns the pixels done (a multiple of 4).
int bayer_row_simd(const ushort* l0, const ushort* l1, int width, const int (&chan)[4], const float (&blk)[4],
                   const float (&thr)[4], const std::array<float, 3>& ic, float* out, std::uint8_t* sat) {
  using namespace simd4;
  f4 b[4], t[4], bit[4], mask[3][4], scale[3];
  for (int k = 0; k < 4; ++k) {
    b[k] = splat(blk[k]);
    t[k] = splat(thr[k]);
    bit[k] = bits(1u << chan[k]);
    for (int c = 0; c < 3; ++c) mask[c][k] = bits(chan[k] == c ? ~0u : 0u);
  }
  for (int c = 0; c < 3; ++c) scale[c] = splat(ic[c]);
  const int n = width & ~3;
  for (int x = 0; x < n; x += 4) {
    f4 v[4];
    load_u16_pairs(l0 + 2 * x, v[0], v[1]);
    load_u16_pairs(l1 + 2 * x, v[2], v[3]);
    f4 s = bits(0);
    for (int k = 0; k < 4; ++k) {
      v[k] = sub(v[k], b[k]);
      s = bit_or(s, bit_and(ge(v[k], t[k]), bit[k]));
    }
    f4 o[3];
    for (int c = 0; c < 3; ++c)
      o[c] = mul(add(add(add(bit_and(v[0], mask[c][0]), bit_and(v[1], mask[c][1])), bit_and(v[2], mask[c][2])),
                     bit_and(v[3], mask[c][3])),
                 scale[c]);
    store_xyz(out + 3 * x, o[0], o[1], o[2]);
    store_bytes(sat + x, s);
  }
  return n;
}
#endif

RawImage build_image(LibRaw& p, const DecodeOptions& options) {
  const LayoutInfo L = classify(p);
  RawImage img;
  fill_metadata(p, L, img.meta);
  const auto& S = p.imgdata.sizes;
  const auto& R = p.imgdata.rawdata;
  const BlackModel black = black_model(p);
  const double white = p.imgdata.color.maximum;
  const double frac = options.saturation_fraction;
  img.width = img.meta.width;
  img.height = img.meta.height;
  if (img.width < 1 || img.height < 1)
    throw Error(ErrorCode::RawCorrupt, "the RAW image is smaller than one CFA block");
  const size_t npix = static_cast<size_t>(img.width) * img.height;
  detail::assign_large(img.rgb, npix * 3, 0.0f);  // pages mapped in one call natively (large_buffer.hpp)
  detail::assign_large(img.saturated, npix, std::uint8_t{0});

  // Black and saturation per channel, reported in metadata (means over the CFA repeat).
  std::array<double, 3> bsum{}, bcount{};
  std::array<double, 4> cfa_black{};

  if (L.layout == "bayer" || L.layout == "xtrans") {
    const int P = L.period, B = L.block;
    // Per CFA position: channel, black, saturation threshold in raw DN. The repeat pattern of
    // black (cblack[4], cblack[5]) may be coarser than the CFA: fold it in per pixel when present.
    const bool pattern_black = black.rep_h > 0;
    std::vector<float> pos_black(static_cast<size_t>(P) * P);
    for (int r = 0; r < P; ++r)
      for (int c = 0; c < P; ++c) {
        const double b = black.at(r, c, p.COLOR(r, c));
        pos_black[r * P + c] = static_cast<float>(b);
        bsum[L.channel[r * P + c]] += b;
        bcount[L.channel[r * P + c]] += 1;
        if (L.layout == "bayer") cfa_black[r * 2 + c] = b;
      }
    // Counts of each channel in a block at each block position (X-Trans blocks differ).
    const int nbx = P / B;
    std::vector<std::array<float, 3>> inv_count(static_cast<size_t>(nbx) * nbx);
    for (int by = 0; by < nbx; ++by)
      for (int bx = 0; bx < nbx; ++bx) {
        std::array<int, 3> n{};
        for (int r = 0; r < B; ++r)
          for (int c = 0; c < B; ++c) ++n[L.channel[(by * B + r) * P + bx * B + c]];
        for (int ch = 0; ch < 3; ++ch) inv_count[by * nbx + bx][ch] = 1.0f / static_cast<float>(n[ch]);
      }
    const size_t pitch = S.raw_pitch / 2;
    const ushort* raw = R.raw_image;
    if (L.layout == "bayer" && !pattern_black) {
      // Fast path: the 2×2 block's positions are fixed (blocks start at even rows and columns).
      int chan[4];
      float blk[4], thr[4];
      for (int k = 0; k < 4; ++k) {
        chan[k] = L.channel[k];
        blk[k] = pos_black[k];
        thr[k] = static_cast<float>(frac * (white - pos_black[k]));
      }
      const auto& ic = inv_count[0];
      for (int y = 0; y < img.height; ++y) {
        const ushort* l0 = raw + static_cast<size_t>(2 * y + S.top_margin) * pitch + S.left_margin;
        const ushort* l1 = l0 + pitch;
        float* out = &img.rgb[static_cast<size_t>(y) * img.width * 3];
        std::uint8_t* sat = &img.saturated[static_cast<size_t>(y) * img.width];
#ifdef TRISTIM_SIMD4
        const int done = bayer_row_simd(l0, l1, img.width, chan, blk, thr, ic, out, sat);
#else
        const int done = 0;
#endif
        for (int x = done; x < img.width; ++x) {
          const float v[4] = {l0[2 * x] - blk[0], l0[2 * x + 1] - blk[1], l1[2 * x] - blk[2],
                              l1[2 * x + 1] - blk[3]};
          float acc[3] = {0.f, 0.f, 0.f};
          std::uint8_t s = 0;
          for (int k = 0; k < 4; ++k) {
            acc[chan[k]] += v[k];
            if (v[k] >= thr[k]) s |= static_cast<std::uint8_t>(1u << chan[k]);
          }
          out[3 * x] = acc[0] * ic[0];
          out[3 * x + 1] = acc[1] * ic[1];
          out[3 * x + 2] = acc[2] * ic[2];
          sat[x] = s;
        }
      }
    } else {
    std::vector<float> sum(static_cast<size_t>(img.width) * 3);
    std::vector<std::uint8_t> sat(img.width);
    for (int y = 0; y < img.height; ++y) {
      std::fill(sum.begin(), sum.end(), 0.0f);
      std::fill(sat.begin(), sat.end(), 0);
      for (int r = 0; r < B; ++r) {
        const int row = y * B + r;
        const ushort* line = raw + static_cast<size_t>(row + S.top_margin) * pitch + S.left_margin;
        const int pr = row % P;
        for (int x = 0; x < img.width; ++x) {
          for (int c = 0; c < B; ++c) {
            const int col = x * B + c;
            const int pos = pr * P + col % P;
            const int ch = L.channel[pos];
            const float b = pattern_black ? static_cast<float>(black.at(row, col, p.COLOR(row, col)))
                                          : pos_black[pos];
            const float v = static_cast<float>(line[col]) - b;
            sum[x * 3 + ch] += v;
            if (v >= frac * (white - b)) sat[x] |= static_cast<std::uint8_t>(1u << ch);
          }
        }
      }
      const int byy = (y * B % P) / B;
      float* out = &img.rgb[static_cast<size_t>(y) * img.width * 3];
      for (int x = 0; x < img.width; ++x) {
        const auto& ic = inv_count[byy * nbx + (x * B % P) / B];
        for (int ch = 0; ch < 3; ++ch) out[x * 3 + ch] = sum[x * 3 + ch] * ic[ch];
        img.saturated[static_cast<size_t>(y) * img.width + x] = sat[x];
      }
    }
    }  // generic CFA path
  } else {
    // linear (3 colours per pixel) or monochrome: one sensor pixel per measurement pixel.
    const bool mono = L.layout == "monochrome";
    const size_t width4 = S.raw_pitch / (mono ? 2 : (R.color4_image ? 8 : 6));
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        const size_t src = static_cast<size_t>(y + S.top_margin) * width4 + x + S.left_margin;
        const size_t dst = static_cast<size_t>(y) * img.width + x;
        std::uint8_t s = 0;
        for (int ch = 0; ch < 3; ++ch) {
          double v;
          if (mono) v = R.raw_image[src];
          else if (R.color4_image) v = R.color4_image[src][ch];
          else v = R.color3_image[src][ch];
          const double b = black.at(y, x, mono ? 0 : ch);
          const double vb = v - b;
          img.rgb[dst * 3 + ch] = static_cast<float>(vb);
          if (vb >= frac * (white - b)) s |= static_cast<std::uint8_t>(1u << ch);
        }
        img.saturated[dst] = s;
      }
    for (int ch = 0; ch < 3; ++ch) {
      bsum[ch] = black.at(0, 0, mono ? 0 : ch);
      bcount[ch] = 1;
    }
    for (int i = 0; i < 4; ++i) cfa_black[i] = black.at(0, 0, mono ? 0 : std::min(i, 2));
  }
  for (int ch = 0; ch < 3; ++ch) {
    img.meta.black_level[ch] = bcount[ch] > 0 ? bsum[ch] / bcount[ch] : 0.0;
    img.meta.saturation[ch] = white - img.meta.black_level[ch];
  }
  img.meta.cfa_black = cfa_black;
  if (!(white > img.meta.black_level[1]))
    throw Error(ErrorCode::RawCorrupt, "the RAW white level is not above its black level");
  return img;
}

}  // namespace

RawImage decode_raw(const std::uint8_t* data, std::size_t size, const DecodeOptions& options) {
  auto proc = open_and_unpack(data, size, options, true);
  RawImage img = build_image(*proc, options);
  return img;
}

bool libraw_identifies(const std::uint8_t* data, std::size_t size, int* raw_width, int* raw_height) {
  if (data == nullptr || size < 64) return false;
  LibRawPtr proc = make_libraw();  // large: not on the (wasm) stack
  if (open_memory(*proc, data, size) != LIBRAW_SUCCESS) return false;
  if (raw_width) *raw_width = proc->imgdata.sizes.raw_width;
  if (raw_height) *raw_height = proc->imgdata.sizes.raw_height;
  return true;
}

namespace fields {
using M = RawMetadata;
TRISTIM_FIELDS_DEFINE(M, member<&M::format>("format"), member<&M::encoding>("encoding"),
                      member<&M::declared_colour>("declared_colour"), member<&M::make>("make"),
                      member<&M::model>("model"), member<&M::lens>("lens"), member<&M::iso>("iso"),
                      member<&M::shutter_s>("shutter_s"), member<&M::f_number>("f_number"),
                      member<&M::timestamp>("timestamp"), member<&M::timestamp_iso>("timestamp_iso"),
                      member<&M::layout>("layout"), member<&M::cfa_pattern>("cfa_pattern"),
                      member<&M::cfa_width>("cfa_width"), member<&M::cfa_height>("cfa_height"),
                      member<&M::block>("block"), member<&M::sensor_width>("sensor_width"),
                      member<&M::sensor_height>("sensor_height"), member<&M::raw_width>("raw_width"),
                      member<&M::raw_height>("raw_height"), member<&M::width>("width"),
                      member<&M::height>("height"), member<&M::bits>("bits"), member<&M::flip>("flip"),
                      member<&M::cfa_black>("cfa_black"), member<&M::black_level>("black_level"),
                      member<&M::white_level>("white_level"), member<&M::saturation>("saturation"),
                      member<&M::rgb_cam>("rgb_cam"), member<&M::cam_xyz>("cam_xyz"),
                      member<&M::as_shot_wb>("as_shot_wb"), member<&M::daylight_wb>("daylight_wb"),
                      member<&M::decoder>("decoder"));
}  // namespace fields

RawMetadata inspect_raw(const std::uint8_t* data, std::size_t size, const DecodeOptions& options) {
  // Black levels of some cameras come from masked pixels read by unpack(): unpack, then describe.
  auto proc = open_and_unpack(data, size, options, true);
  return build_image(*proc, options).meta;
}

std::string metadata_to_json(const RawMetadata& m) { return fields::write(m).dump(); }

namespace {

/// The image pixels behind preview pixel (i, j): a scale × scale block, cut at the image's edge.
/// A side shorter than the scale (a 8076 × 11 strip previewed at 64 px: scale 127, one preview
/// row) is one preview pixel over the whole side — the block used to run past the image's last
/// row (fuzz_raw: heap-buffer-overflow, tests/fuzz/corpus/raw/crash-d474b658…).
struct PreviewBlock {
  int x0, x1, y0, y1;
  int count() const { return (x1 - x0) * (y1 - y0); }
  /// Sum of the image's R, G, B over the block.
  std::array<double, 3> sum(const RawImage& image) const {
    std::array<double, 3> acc{0, 0, 0};
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x)
        for (int c = 0; c < 3; ++c) acc[c] += image.at(x, y, c);
    return acc;
  }
};
PreviewBlock preview_block(const RawImage& image, int scale, int i, int j) {
  return {i * scale, std::min((i + 1) * scale, image.width), j * scale, std::min((j + 1) * scale, image.height)};
}

}  // namespace

Preview render_preview(const RawImage& image, int max_side) {
  if (max_side < 1) throw Error(ErrorCode::InvalidArgument, "preview size must be at least 1 pixel");
  if (image.width < 1 || image.height < 1) throw Error(ErrorCode::InvalidArgument, "empty image");
  Preview pv;
  const int longest = std::max(image.width, image.height);
  pv.scale = std::max(1, (longest + max_side - 1) / max_side);
  pv.width = std::max(1, image.width / pv.scale);
  pv.height = std::max(1, image.height / pv.scale);
  const auto& m = image.meta;
  if (m.encoding == "stored") {
    // An image's stored values are already display-encoded: shown as they are (box mean / full
    // scale), no white balance, matrix, exposure or transfer curve.
    const double fs = m.white_level > 0 ? m.white_level : 255.0;
    pv.rgba.resize(static_cast<size_t>(pv.width) * pv.height * 4);
    for (int j = 0; j < pv.height; ++j)
      for (int i = 0; i < pv.width; ++i) {
        const PreviewBlock b = preview_block(image, pv.scale, i, j);
        const double inv_n = 1.0 / static_cast<double>(b.count());
        const std::array<double, 3> acc = b.sum(image);
        std::uint8_t* px = &pv.rgba[(static_cast<size_t>(j) * pv.width + i) * 4];
        for (int c = 0; c < 3; ++c)
          px[c] = static_cast<std::uint8_t>(std::lround(std::min(1.0, std::max(0.0, acc[c] * inv_n / fs)) * 255.0));
        px[3] = 255;
      }
    return pv;
  }
  std::array<double, 3> wb = m.as_shot_wb;
  for (double& w : wb)
    if (!(w > 0) || !std::isfinite(w)) w = 1.0;
  std::array<double, 9> M = m.rgb_cam;
  bool matrix_ok = false;
  for (double v : M) matrix_ok = matrix_ok || (v != 0 && std::isfinite(v));
  if (!matrix_ok) M = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  const double sat = std::max(1.0, m.saturation[1]);
  const size_t n = static_cast<size_t>(pv.width) * pv.height;
  std::vector<float> lin(n * 3);
  std::vector<float> lum(n);
  for (int j = 0; j < pv.height; ++j)
    for (int i = 0; i < pv.width; ++i) {
      const PreviewBlock b = preview_block(image, pv.scale, i, j);
      const float inv = 1.0f / static_cast<float>(b.count());
      const std::array<double, 3> acc = b.sum(image);
      double cam[3];
      for (int c = 0; c < 3; ++c) cam[c] = std::max(0.0, acc[c] * inv * wb[c] / sat);
      const size_t k = static_cast<size_t>(j) * pv.width + i;
      for (int r = 0; r < 3; ++r)
        lin[k * 3 + r] = static_cast<float>(M[r * 3] * cam[0] + M[r * 3 + 1] * cam[1] + M[r * 3 + 2] * cam[2]);
      lum[k] = 0.2126f * lin[k * 3] + 0.7152f * lin[k * 3 + 1] + 0.0722f * lin[k * 3 + 2];
    }
  std::vector<float> sorted = lum;
  const double p99 = percentile(sorted, 0.99);
  const double gain = p99 > 1e-9 ? 0.9 / p99 : 1.0;
  pv.rgba.resize(n * 4);
  for (size_t k = 0; k < n; ++k) {
    for (int c = 0; c < 3; ++c) {
      const double v = sRGB_encode(lin[k * 3 + c] * gain);
      pv.rgba[k * 4 + c] = static_cast<std::uint8_t>(std::lround(v * 255.0));
    }
    pv.rgba[k * 4 + 3] = 255;
  }
  return pv;
}

std::uint64_t linear_data_hash(const RawImage& image) {
  std::uint64_t h = 1469598103934665603ull;
  const auto mix = [&h](const void* p, size_t n) {
    const auto* b = static_cast<const std::uint8_t*>(p);
    for (size_t i = 0; i < n; ++i) {
      h ^= b[i];
      h *= 1099511628211ull;
    }
  };
  const std::int32_t dims[2] = {image.width, image.height};
  mix(dims, sizeof dims);
  mix(image.rgb.data(), image.rgb.size() * sizeof(float));
  return h;
}

std::string hash_hex(std::uint64_t hash) {
  char buf[20];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(hash));
  return buf;
}

}  // namespace tristim
