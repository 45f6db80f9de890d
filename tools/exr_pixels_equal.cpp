// exr_pixels_equal A.exr B.exr: are the pixels of two OpenEXR files
// bit-identical? Compares the channel lists (names, pixel types, sampling),
// the data windows and every stored value's raw bits, and nothing else of the
// headers (spectrace's hold wall time, dates and such).
//
// Exit status: 0 equal; 1 different (the first difference, in channel-name,
// then scanline order, is printed with the number of differing values);
// 2 usage or read error.
#include <Iex.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfPixelType.h>
#include <half.h>

#include <cinttypes>
#include <cstdint>
#include <cstdio>
#include <algorithm>
#include <cstring>
#include <exception>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

struct ChannelData {
  std::string name;
  Imf::Channel channel;
  std::int64_t columns = 0;     // stored samples per row (data window width / xSampling)
  std::int64_t rows = 0;        // stored rows (height / ySampling)
  std::vector<std::uint8_t> bytes;  // columns * rows values of the channel's own type
};

struct Image {
  std::unique_ptr<Imf::InputFile> file;
  Imath::Box2i dataWindow;
  std::vector<ChannelData> channels;  // ChannelList order: by name
};

std::size_t typeSize(Imf::PixelType type) { return type == Imf::HALF ? 2 : 4; }

const char* typeName(Imf::PixelType type) {
  switch (type) {
    case Imf::UINT: return "uint";
    case Imf::HALF: return "half";
    case Imf::FLOAT: return "float";
    default: return "?";
  }
}

std::string describeChannels(const Imf::ChannelList& list) {
  std::string text;
  for (auto it = list.begin(); it != list.end(); ++it) {
    if (!text.empty()) text += ", ";
    text += it.name();
    text += ":";
    text += typeName(it.channel().type);
    if (it.channel().xSampling != 1 || it.channel().ySampling != 1) {
      text += '/';
      text += std::to_string(it.channel().xSampling);
      text += 'x';
      text += std::to_string(it.channel().ySampling);
    }
  }
  return text.empty() ? "(none)" : text;
}

bool sameChannels(const Imf::ChannelList& a, const Imf::ChannelList& b) {
  auto ia = a.begin();
  auto ib = b.begin();
  for (; ia != a.end() && ib != b.end(); ++ia, ++ib) {
    if (std::strcmp(ia.name(), ib.name()) != 0) return false;
    const Imf::Channel& ca = ia.channel();
    const Imf::Channel& cb = ib.channel();
    if (ca.type != cb.type || ca.xSampling != cb.xSampling || ca.ySampling != cb.ySampling ||
        ca.pLinear != cb.pLinear) {
      return false;
    }
  }
  return ia == a.end() && ib == b.end();
}

std::string describeWindow(const Imath::Box2i& w) {
  return "(" + std::to_string(w.min.x) + "," + std::to_string(w.min.y) + ")-(" + std::to_string(w.max.x) + "," +
         std::to_string(w.max.y) + ")";
}

// Opens the file and reads its header; throws on error.
Image openImage(const char* path) {
  Image image;
  image.file = std::make_unique<Imf::InputFile>(path);
  image.dataWindow = image.file->header().dataWindow();
  return image;
}

// Reads every channel's stored values, each in its own pixel type, so that
// nothing is converted before the comparison.
// `only`: when not null, the channels to read (the others are skipped).
void readPixels(Image& image, const std::vector<std::string>* only = nullptr) {
  const Imath::Box2i& dw = image.dataWindow;
  const std::int64_t width = std::int64_t{dw.max.x} - dw.min.x + 1;
  const std::int64_t height = std::int64_t{dw.max.y} - dw.min.y + 1;
  if (width <= 0 || height <= 0) throw std::runtime_error("empty data window " + describeWindow(dw));
  Imf::FrameBuffer frame;
  const Imf::ChannelList& list = image.file->header().channels();
  std::size_t channelCount = 0;
  for (auto it = list.begin(); it != list.end(); ++it) ++channelCount;
  image.channels.reserve(channelCount);  // the frame buffer points into each channel's bytes
  for (auto it = list.begin(); it != list.end(); ++it) {
    if (only && std::find(only->begin(), only->end(), std::string(it.name())) == only->end()) continue;
    ChannelData& ch = image.channels.emplace_back();
    ch.name = it.name();
    ch.channel = it.channel();
    // OpenEXR requires the data window's origin and size to be multiples of
    // the sampling rates.
    ch.columns = width / ch.channel.xSampling;
    ch.rows = height / ch.channel.ySampling;
    const std::size_t size = typeSize(ch.channel.type);
    ch.bytes.assign(static_cast<std::size_t>(ch.columns * ch.rows) * size, 0);
    frame.insert(ch.name, Imf::Slice::Make(ch.channel.type, ch.bytes.data(), dw, size,
                                           size * static_cast<std::size_t>(ch.columns), ch.channel.xSampling,
                                           ch.channel.ySampling));
  }
  image.file->setFrameBuffer(frame);
  image.file->readPixels(dw.min.y, dw.max.y);
}

std::uint32_t bitsAt(const ChannelData& ch, std::size_t index) {
  if (ch.channel.type == Imf::HALF) {
    std::uint16_t v;
    std::memcpy(&v, ch.bytes.data() + index * 2, 2);
    return v;
  }
  std::uint32_t v;
  std::memcpy(&v, ch.bytes.data() + index * 4, 4);
  return v;
}

std::string formatValue(Imf::PixelType type, std::uint32_t bits) {
  char text[64];
  switch (type) {
    case Imf::UINT:
      std::snprintf(text, sizeof text, "%" PRIu32, bits);
      break;
    case Imf::HALF: {
      half h;
      h.setBits(static_cast<std::uint16_t>(bits));
      std::snprintf(text, sizeof text, "%.5g (0x%04" PRIx32 ")", static_cast<double>(static_cast<float>(h)), bits);
      break;
    }
    default: {
      float f;
      std::memcpy(&f, &bits, sizeof f);
      std::snprintf(text, sizeof text, "%.9g (0x%08" PRIx32 ")", static_cast<double>(f), bits);
      break;
    }
  }
  return text;
}


// The names of the channels both lists hold, and a note of the others.
std::vector<std::string> sharedChannels(const Imf::ChannelList& a, const Imf::ChannelList& b, std::string& others) {
  std::vector<std::string> shared;
  for (auto it = a.begin(); it != a.end(); ++it) {
    if (b.findChannel(it.name())) shared.emplace_back(it.name());
    else others += std::string(others.empty() ? "" : ", ") + it.name() + " (first only)";
  }
  for (auto it = b.begin(); it != b.end(); ++it)
    if (!a.findChannel(it.name())) others += std::string(others.empty() ? "" : ", ") + it.name() + " (second only)";
  return shared;
}

Imf::ChannelList restricted(const Imf::ChannelList& list, const std::vector<std::string>& names) {
  Imf::ChannelList out;
  for (auto it = list.begin(); it != list.end(); ++it)
    if (std::find(names.begin(), names.end(), std::string(it.name())) != names.end()) out.insert(it.name(), it.channel());
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  // --shared-channels: compare only the channels both files have (a change
  // that adds channels must still leave the old ones bit-identical).
  const bool sharedOnly = argc == 4 && std::strcmp(argv[1], "--shared-channels") == 0;
  if ((argc != 3 && !sharedOnly) || std::strcmp(argv[1], "-h") == 0 || std::strcmp(argv[1], "--help") == 0) {
    std::fprintf(stderr,
                 "usage: %s [--shared-channels] A.exr B.exr\n"
                 "Exits 0 if both files have the same channels (or, with --shared-channels, for the\n"
                 "channels both have), data window and bit-identical pixel values, 1 if not (printing\n"
                 "the first difference), 2 on a usage or read error.\n",
                 argc > 0 ? argv[0] : "exr_pixels_equal");
    return 2;
  }
  const char* pathA = argv[sharedOnly ? 2 : 1];
  const char* pathB = argv[sharedOnly ? 3 : 2];

  Image a;
  Image b;
  const char* current = pathA;
  try {
    a = openImage(pathA);
    current = pathB;
    b = openImage(pathB);
  } catch (const std::exception& e) {  // Iex::BaseExc derives from std::exception
    std::fprintf(stderr, "exr_pixels_equal: cannot read %s: %s\n", current, e.what());
    return 2;
  }

  std::vector<std::string> shared;
  std::string others;
  Imf::ChannelList channelsA = a.file->header().channels();
  Imf::ChannelList channelsB = b.file->header().channels();
  if (sharedOnly) {
    shared = sharedChannels(channelsA, channelsB, others);
    channelsA = restricted(channelsA, shared);
    channelsB = restricted(channelsB, shared);
  }
  if (!sameChannels(channelsA, channelsB)) {
    std::printf("channel lists differ: %s has [%s], %s has [%s]\n", pathA, describeChannels(channelsA).c_str(),
                pathB, describeChannels(channelsB).c_str());
    return 1;
  }
  if (a.dataWindow != b.dataWindow) {
    std::printf("data windows differ: %s has %s, %s has %s\n", pathA, describeWindow(a.dataWindow).c_str(), pathB,
                describeWindow(b.dataWindow).c_str());
    return 1;
  }

  try {
    current = pathA;
    readPixels(a, sharedOnly ? &shared : nullptr);
    current = pathB;
    readPixels(b, sharedOnly ? &shared : nullptr);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "exr_pixels_equal: cannot read the pixels of %s: %s\n", current, e.what());
    return 2;
  }

  std::uint64_t differing = 0;
  std::uint64_t total = 0;
  std::string first;
  for (std::size_t c = 0; c < a.channels.size(); ++c) {
    const ChannelData& ca = a.channels[c];
    const ChannelData& cb = b.channels[c];
    const std::size_t count = static_cast<std::size_t>(ca.columns * ca.rows);
    total += count;
    if (std::memcmp(ca.bytes.data(), cb.bytes.data(), ca.bytes.size()) == 0) continue;
    for (std::size_t i = 0; i < count; ++i) {
      const std::uint32_t va = bitsAt(ca, i);
      const std::uint32_t vb = bitsAt(cb, i);
      if (va == vb) continue;
      if (differing++ == 0) {
        // Pixel coordinates in the data window (of the first sample a
        // subsampled value covers).
        const std::int64_t x = a.dataWindow.min.x + static_cast<std::int64_t>(i % static_cast<std::size_t>(ca.columns)) *
                                                         ca.channel.xSampling;
        const std::int64_t y = a.dataWindow.min.y + static_cast<std::int64_t>(i / static_cast<std::size_t>(ca.columns)) *
                                                         ca.channel.ySampling;
        first = "channel " + ca.name + " at x=" + std::to_string(x) + " y=" + std::to_string(y) + ": " +
                formatValue(ca.channel.type, va) + " vs " + formatValue(cb.channel.type, vb);
      }
    }
  }
  if (differing != 0) {
    std::printf("%s (%" PRIu64 " of %" PRIu64 " values differ)\n", first.c_str(), differing, total);
    return 1;
  }
  if (!others.empty()) std::printf("compared the shared channels; not compared: %s\n", others.c_str());
  return 0;
}
