// OpenEXR output and input of RenderImage (float32, lossless ZIP).
#include <Iex.h>
#include <ImfChannelList.h>
#include <ImfChromaticities.h>
#include <ImfDoubleAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStandardAttributes.h>
#include <ImfStringAttribute.h>
#include <ImfThreading.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <map>
#include <string>
#include <thread>
#include <utility>

#include "io/atomic_file.h"
#include "io/image.h"

namespace spectrace {
namespace {

struct ChannelSpec {
  const char* name;
  std::vector<float> RenderImage::*data;
  int components;  // interleaved floats per pixel in that vector
  int index;       // which of them
};

constexpr ChannelSpec kChannels[] = {
    {"R", &RenderImage::rgb, 3, 0},          {"G", &RenderImage::rgb, 3, 1},
    {"B", &RenderImage::rgb, 3, 2},          {"XYZ.X", &RenderImage::xyz, 3, 0},
    {"XYZ.Y", &RenderImage::xyz, 3, 1},      {"XYZ.Z", &RenderImage::xyz, 3, 2},
    {"irradiance.E", &RenderImage::irradiance, 1, 0},
};

// Imf::OStream over the temp file's descriptor. OpenEXR writes the line
// offset table in ~OutputFile and swallows any error there, so the stream
// remembers failures itself; otherwise a truncated file could be committed.
class FdOStream final : public Imf::OStream {
 public:
  FdOStream(int fd, const std::string& name) : Imf::OStream(name.c_str()), fd_(fd) {}

  void write(const char c[], int n) override {
    if (n < 0) fail("negative write size");
    if (const int err = io_detail::pwriteAll(fd_, c, static_cast<std::size_t>(n), pos_)) {
      fail(io_detail::errnoText(err));
    }
    pos_ += static_cast<std::uint64_t>(n);
  }
  std::uint64_t tellp() override { return pos_; }
  void seekp(std::uint64_t pos) override { pos_ = pos; }  // pwrite needs no lseek

  const std::string& error() const { return error_; }

 private:
  [[noreturn]] void fail(const std::string& why) {
    if (error_.empty()) error_ = why;
    throw Iex::IoExc(why);
  }

  int fd_;
  std::uint64_t pos_ = 0;
  std::string error_;
};

constexpr const char* kErrorChannel = "error.E";
// The spectral layout's header attributes (Fichet, Pacanowski, Wilkie 2021).
constexpr const char* kSpectralLayoutVersion = "spectralLayoutVersion";
// Spectral irradiance, which the channels hold (not the layout's radiance,
// W.m^-2.sr^-1: the film counts power per area, with no solid angle).
constexpr const char* kEmissiveUnits = "emissiveUnits";

// R, G, B are linear sRGB: Rec. 709 primaries and D65 white, those
// xyzToLinearSrgb (colour/) is derived from. Set explicitly, not left to
// Imf::Chromaticities' defaults, so the values are ours whatever they hold.
const Imf::Chromaticities kRec709D65{Imath::V2f(0.64f, 0.33f), Imath::V2f(0.30f, 0.60f),
                                     Imath::V2f(0.15f, 0.06f), Imath::V2f(0.3127f, 0.3290f)};

// The wavelength of a spectral layout channel name "S0.<nm>nm", or a
// negative value when the name is not one.
double wavelengthOfSpectralChannel(const std::string& name) {
  const std::string prefix = "S0.", suffix = "nm";
  if (name.size() <= prefix.size() + suffix.size() || name.compare(0, prefix.size(), prefix) != 0 ||
      name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
    return -1.0;
  std::string number = name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
  std::replace(number.begin(), number.end(), ',', '.');
  char* end = nullptr;
  const double nm = std::strtod(number.c_str(), &end);
  return end == number.c_str() + number.size() && nm > 0.0 ? nm : -1.0;
}

[[noreturn]] void readFail(const std::filesystem::path& path, const std::string& why) {
  throw ImageIoError("cannot read EXR " + path.string() + ": " + why);
}

}  // namespace

std::string spectralChannelName(double wavelengthNm) {
  char text[64];
  std::snprintf(text, sizeof text, "S0.%.6fnm", wavelengthNm);  // "C" locale: '.' as separator
  std::string name = text;
  std::replace(name.begin(), name.end(), '.', ',');
  name[2] = '.';  // the layer separator after "S0" stays a dot
  return name;
}

std::optional<SpectralChannelClash> spectralChannelClash(const std::vector<double>& centresNm) {
  std::map<std::string, std::size_t> seen;
  for (std::size_t b = 0; b < centresNm.size(); ++b) {
    std::string name = spectralChannelName(centresNm[b]);
    const auto [it, added] = seen.emplace(name, b);
    if (!added) return SpectralChannelClash{it->second, b, std::move(name)};
  }
  return std::nullopt;
}

void writeExr(const std::filesystem::path& path, const RenderImage& image, const ImageMetadata& meta) {
  const auto writeError = [&](const std::string& why) {
    return ImageIoError("cannot write EXR " + path.string() + ": " + why);
  };
  // Validate before creating anything on disk.
  if (image.width <= 0 || image.height <= 0) {
    throw writeError("image size " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                    " is not positive");
  }
  const std::size_t pixels = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
  const auto checkSize = [&](const char* field, std::size_t actual, std::size_t perPixel) {
    if (actual != pixels * perPixel) {
      throw writeError(std::string(field) + " has " + std::to_string(actual) + " floats, expected " +
                      std::to_string(pixels * perPixel) + " (" + std::to_string(image.width) + "x" +
                      std::to_string(image.height) + "x" + std::to_string(perPixel) + ")");
    }
  };
  checkSize("rgb", image.rgb.size(), 3);
  checkSize("xyz", image.xyz.size(), 3);
  checkSize("irradiance", image.irradiance.size(), 1);
  if (!image.irradianceError.empty()) checkSize("irradianceError", image.irradianceError.size(), 1);
  const std::size_t bins = image.spectralBinCentresNm.size();
  std::vector<std::string> spectralNames;
  if (bins > 0 || !image.spectralIrradiance.empty()) {
    if (bins == 0) throw writeError("spectralIrradiance is given without spectralBinCentresNm");
    checkSize("spectralIrradiance", image.spectralIrradiance.size(), bins);
    for (const double nm : image.spectralBinCentresNm) {
      if (!(nm > 0.0)) throw writeError("spectral bin centre " + std::to_string(nm) + " nm is not positive");
      spectralNames.push_back(spectralChannelName(nm));
    }
    if (const auto clash = spectralChannelClash(image.spectralBinCentresNm))
      throw writeError("two spectral bins share the channel name " + clash->name);
  }

  try {
    Imf::Header header(image.width, image.height);  // data window (0,0)..(w-1,h-1), INCREASING_Y
    header.compression() = Imf::ZIP_COMPRESSION;    // lossless, so floats round-trip bit-exactly
    Imf::addChromaticities(header, kRec709D65);     // what R, G, B mean, for colour-managed readers
    // Reject user names that collide with standard attributes or with each
    // other: Header::insert would either throw a cryptic type error or
    // silently replace one value.
    const auto addAttribute = [&](const std::string& name, const Imf::Attribute& attr) {
      if (name.empty()) throw writeError("metadata attribute with an empty name");
      if (header.find(name) != header.end()) {
        throw writeError("metadata attribute \"" + name + "\" clashes with a standard or duplicate attribute");
      }
      header.insert(name, attr);
    };
    for (const auto& [name, value] : meta.strings) addAttribute(name, Imf::StringAttribute(value));
    for (const auto& [name, value] : meta.numbers) addAttribute(name, Imf::DoubleAttribute(value));

    Imf::FrameBuffer frame;
    for (const ChannelSpec& ch : kChannels) {
      header.channels().insert(ch.name, Imf::Channel(Imf::FLOAT));
      // Slices take a non-const pointer for both directions; OutputFile only reads through it.
      const std::vector<float>& data = image.*ch.data;
      char* base = reinterpret_cast<char*>(const_cast<float*>(data.data() + ch.index));
      const std::size_t xStride = sizeof(float) * static_cast<std::size_t>(ch.components);
      frame.insert(ch.name, Imf::Slice(Imf::FLOAT, base, xStride, xStride * static_cast<std::size_t>(image.width)));
    }
    const auto insertChannel = [&](const std::string& name, const float* first, std::size_t components) {
      header.channels().insert(name, Imf::Channel(Imf::FLOAT));
      char* base = reinterpret_cast<char*>(const_cast<float*>(first));
      const std::size_t xStride = sizeof(float) * components;
      frame.insert(name, Imf::Slice(Imf::FLOAT, base, xStride, xStride * static_cast<std::size_t>(image.width)));
    };
    if (!image.irradianceError.empty()) insertChannel(kErrorChannel, image.irradianceError.data(), 1);
    if (bins > 0) {
      addAttribute(kSpectralLayoutVersion, Imf::StringAttribute("1.0"));
      addAttribute(kEmissiveUnits, Imf::StringAttribute("W.m^-2.nm^-1"));
      for (std::size_t b = 0; b < bins; ++b) insertChannel(spectralNames[b], image.spectralIrradiance.data() + b, bins);
    }

    // ZIP compresses blocks of 16 rows independently: with OpenEXR's thread
    // pool on every core, writing a large image takes about 1 / cores of
    // the time (one thread by default). Set once, for the whole process.
    static const bool threadsSet = [] {
      Imf::setGlobalThreadCount(int(std::max(1u, std::thread::hardware_concurrency())));
      return true;
    }();
    (void)threadsSet;

    // Only now touch the disk; an exception from here on removes the temp
    // file (~AtomicFile) before it propagates.
    io_detail::AtomicFile file(path, "EXR");
    FdOStream stream(file.fd(), file.tempPath().string());
    {
      Imf::OutputFile out(stream, header);
      out.setFrameBuffer(frame);
      out.writePixels(image.height);
    }  // ~OutputFile writes the offset table; failures are only visible via stream.error()
    if (!stream.error().empty()) file.fail(stream.error());
    file.commit();
  } catch (const ImageIoError&) {
    throw;
  } catch (const std::exception& e) {  // Iex::BaseExc derives from std::exception
    throw writeError(e.what());
  }
}

ExrContents readExr(const std::filesystem::path& path) {
  try {
    Imf::InputFile in(path.c_str());
    const Imf::Header& header = in.header();
    const Imath::Box2i dw = header.dataWindow();
    const std::int64_t width = std::int64_t{dw.max.x} - dw.min.x + 1;
    const std::int64_t height = std::int64_t{dw.max.y} - dw.min.y + 1;
    if (width <= 0 || height <= 0 || width > INT32_MAX || height > INT32_MAX) {
      readFail(path, "invalid data window");
    }
    // OpenEXR would silently fill a missing channel with zeros; a render
    // file without one is an error.
    for (const ChannelSpec& ch : kChannels) {
      if (!header.channels().findChannel(ch.name)) readFail(path, std::string("missing channel \"") + ch.name + "\"");
    }

    ExrContents result;
    RenderImage& image = result.image;
    image.width = static_cast<int>(width);
    image.height = static_cast<int>(height);
    const auto pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    image.rgb.resize(pixels * 3);
    image.xyz.resize(pixels * 3);
    image.irradiance.resize(pixels);

    Imf::FrameBuffer frame;
    for (const ChannelSpec& ch : kChannels) {
      std::vector<float>& data = image.*ch.data;
      // Slice::Make handles a data window not at the origin without
      // out-of-range pointer arithmetic; stored HALF/UINT channels convert.
      frame.insert(ch.name, Imf::Slice::Make(Imf::FLOAT, data.data() + ch.index, dw,
                                             sizeof(float) * static_cast<std::size_t>(ch.components)));
    }
    if (header.channels().findChannel(kErrorChannel)) {
      image.irradianceError.resize(pixels);
      frame.insert(kErrorChannel, Imf::Slice::Make(Imf::FLOAT, image.irradianceError.data(), dw, sizeof(float)));
    }
    // Spectral layout channels, in order of wavelength.
    std::vector<std::pair<double, std::string>> spectral;
    for (auto it = header.channels().begin(); it != header.channels().end(); ++it) {
      const double nm = wavelengthOfSpectralChannel(it.name());
      if (nm > 0.0) spectral.emplace_back(nm, it.name());
    }
    std::sort(spectral.begin(), spectral.end());
    const std::size_t bins = spectral.size();
    image.spectralIrradiance.resize(pixels * bins);
    for (std::size_t b = 0; b < bins; ++b) {
      image.spectralBinCentresNm.push_back(spectral[b].first);
      frame.insert(spectral[b].second, Imf::Slice::Make(Imf::FLOAT, image.spectralIrradiance.data() + b, dw,
                                                        sizeof(float) * bins));
    }
    in.setFrameBuffer(frame);
    in.readPixels(dw.min.y, dw.max.y);

    // Only string and double attributes are ours; standard ones (box,
    // compression, channel list, ...) have other types and are skipped.
    for (auto it = header.begin(); it != header.end(); ++it) {
      if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute())) {
        result.meta.strings.emplace(it.name(), s->value());
      } else if (const auto* d = dynamic_cast<const Imf::DoubleAttribute*>(&it.attribute())) {
        result.meta.numbers.emplace(it.name(), d->value());
      }
    }
    return result;
  } catch (const ImageIoError&) {
    throw;
  } catch (const std::exception& e) {  // Iex::BaseExc derives from std::exception
    readFail(path, e.what());
  }
}

}  // namespace spectrace
