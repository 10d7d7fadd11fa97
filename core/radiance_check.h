#pragma once
// A structural check of Radiance RGBE (.hdr) data before stb_image decodes it. stb_image 2.27
// (Debian 12) reads past the end of a truncated file as zeros without a word (the missing
// texels come out black), and a scanline whose run-length count byte is 0 (a "dump" of no
// bytes) makes its decoder loop for ever. The check walks the scanlines as stb_image
// reads them, counting bytes, without decoding a value.

#include <cstddef>
#include <string>

namespace tessera {

/// Whether `data` (`size` bytes) starts as a Radiance file does ("#?").
bool looks_like_radiance(const unsigned char* data, size_t size);

/// Why stb_image must not decode `data` (`size` bytes, a whole file), or "" if it may: "" too
/// for data that is not Radiance (looks_like_radiance false), or whose header stb_image will
/// refuse by itself (no "-Y H +X W" resolution line after the header). Otherwise "is truncated:
/// its WxH texels need more than its N bytes" or "has a run-length count of 0 in scanline J
/// (corrupt)". The layout is that of stb_image's reader (its stbi__hdr_load): flat RGBE texels
/// for widths under 8 or from 32768, else per scanline either the marker 2 2 hi lo followed by
/// four run-length encoded channels, or flat texels from there to the end of the image.
/// Source: G. Ward, "Real Pixels" (Graphics Gems II, 1991), and the Radiance file format.
std::string radiance_fault(const unsigned char* data, size_t size);

}  // namespace tessera
