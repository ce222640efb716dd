// SPDX-License-Identifier: BSD-3-Clause
#include "sonargrid/io/bag/codecs.h"

#include <bzlib.h>
#include <lz4frame.h>
#include <zstd.h>

#include <algorithm>
#include <limits>
#include <memory>

namespace sg::bag {
namespace {

void checkSize(std::size_t expectedSize) {
  if (expectedSize > kMaxChunkBytes) {
    throw CodecError("an uncompressed size of " + std::to_string(expectedSize) +
                     " bytes, over the limit of " + std::to_string(kMaxChunkBytes));
  }
}

// The output grows as data come out, from a few times the input up to the declared size, so that
// a corrupt size field on a small chunk costs nothing: nothing is allocated for bytes that never
// come. One spare byte past the declared size tells "more than declared" from "exactly".
class Output {
 public:
  Output(std::string& out, std::size_t expected, std::size_t inputSize)
      : out_(out), limit_(expected + 1) {
    out_.resize(std::min(limit_, std::max<std::size_t>(std::size_t{1} << 16, 8 * inputSize)));
  }
  // Room after `written` bytes, growing the buffer when it is full; 0 once the spare byte is used.
  std::size_t room(std::size_t written) {
    if (written == out_.size() && out_.size() < limit_) {
      out_.resize(std::min(limit_, 2 * out_.size()));
    }
    return out_.size() - written;
  }
  char* at(std::size_t written) { return out_.data() + written; }

 private:
  std::string& out_;
  std::size_t limit_;
};

[[noreturn]] void wrongSize(const char* codec, std::size_t got, std::size_t expected) {
  if (got > expected) {
    throw CodecError(std::string(codec) + " data decompress to more than the " +
                     std::to_string(expected) + " bytes the record declares");
  }
  throw CodecError(std::string(codec) + " data decompress to " + std::to_string(got) +
                   " bytes, not the " + std::to_string(expected) + " the record declares");
}

}  // namespace

void decompressBz2(std::string_view in, std::size_t expectedSize, std::string& out) {
  checkSize(expectedSize);
  if (in.size() > std::numeric_limits<unsigned>::max()) throw CodecError("bz2 block too large");
  bz_stream s{};
  if (BZ2_bzDecompressInit(&s, 0, 0) != BZ_OK) throw CodecError("cannot start bz2 decompression");
  std::unique_ptr<bz_stream, int (*)(bz_stream*)> guard(&s, &BZ2_bzDecompressEnd);
  Output o(out, expectedSize, in.size());
  s.next_in = const_cast<char*>(in.data());
  s.avail_in = static_cast<unsigned>(in.size());
  std::size_t written = 0;
  while (true) {
    const std::size_t room =
        std::min<std::size_t>(o.room(written), std::numeric_limits<unsigned>::max());
    if (room == 0) wrongSize("bz2", written, expectedSize);
    s.next_out = o.at(written);
    s.avail_out = static_cast<unsigned>(room);
    const int status = BZ2_bzDecompress(&s);
    written += room - s.avail_out;
    if (status == BZ_STREAM_END) break;
    if (status != BZ_OK) {
      throw CodecError("corrupt bz2 data (libbz2 error " + std::to_string(status) + ")");
    }
    if (s.avail_in == 0 && s.avail_out != 0) {
      throw CodecError("bz2 data cut short after " + std::to_string(in.size()) + " bytes");
    }
  }
  if (written != expectedSize) wrongSize("bz2", written, expectedSize);
  out.resize(expectedSize);
}

void decompressLz4Frame(std::string_view in, std::size_t expectedSize, std::string& out) {
  checkSize(expectedSize);
  LZ4F_dctx* raw = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&raw, LZ4F_VERSION))) {
    throw CodecError("cannot create an LZ4 decompression context");
  }
  std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> ctx(
      raw, &LZ4F_freeDecompressionContext);
  Output o(out, expectedSize, in.size());
  std::size_t written = 0, consumed = 0;
  while (true) {
    std::size_t dstSize = o.room(written);
    if (dstSize == 0) wrongSize("LZ4", written, expectedSize);
    std::size_t srcSize = in.size() - consumed;
    const std::size_t hint = LZ4F_decompress(ctx.get(), o.at(written), &dstSize,
                                             in.data() + consumed, &srcSize, nullptr);
    if (LZ4F_isError(hint)) {
      throw CodecError(std::string("corrupt LZ4 frame (") + LZ4F_getErrorName(hint) + ")");
    }
    written += dstSize;
    consumed += srcSize;
    if (hint == 0) {
      // A frame ended; anything after it would be a second frame, which bags do not write.
      if (consumed != in.size()) {
        throw CodecError("LZ4 data go on for " + std::to_string(in.size() - consumed) +
                         " bytes after the end of the frame");
      }
      break;
    }
    if (consumed == in.size() && dstSize == 0) {
      throw CodecError("LZ4 frame cut short after " + std::to_string(in.size()) + " bytes");
    }
  }
  if (written != expectedSize) wrongSize("LZ4", written, expectedSize);
  out.resize(expectedSize);
}

void decompressZstd(std::string_view in, std::size_t expectedSize, std::string& out) {
  checkSize(expectedSize);
  std::unique_ptr<ZSTD_DCtx, decltype(&ZSTD_freeDCtx)> ctx(ZSTD_createDCtx(), &ZSTD_freeDCtx);
  if (!ctx) throw CodecError("cannot create a zstd decompression context");
  Output o(out, expectedSize, in.size());
  ZSTD_inBuffer input{in.data(), in.size(), 0};
  std::size_t written = 0;
  while (true) {
    const std::size_t room = o.room(written);
    if (room == 0) wrongSize("zstd", written, expectedSize);
    ZSTD_outBuffer output{o.at(written), room, 0};
    const std::size_t status = ZSTD_decompressStream(ctx.get(), &output, &input);
    if (ZSTD_isError(status)) {
      throw CodecError(std::string("corrupt zstd data (") + ZSTD_getErrorName(status) + ")");
    }
    written += output.pos;
    if (status == 0 && input.pos == input.size) break;  // the last frame ended with the input
    if (input.pos == input.size && output.pos < room) {
      throw CodecError("zstd data cut short after " + std::to_string(in.size()) + " bytes");
    }
  }
  if (written != expectedSize) wrongSize("zstd", written, expectedSize);
  out.resize(expectedSize);
}

}  // namespace sg::bag
