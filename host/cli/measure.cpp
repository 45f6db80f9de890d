// spectrace measure: a lighting engineer's reading of a render's image.
#include <cmath>
#include <cstdio>

#include <fmt/format.h>

#include "cli/cli_numbers.h"
#include "cli/commands.h"
#include "cli/exit_codes.h"
#include "io/image.h"
#include "metrics/false_colour.h"
#include "metrics/illuminance_report.h"

namespace spectrace::cli {

int runMeasure(const MeasureCommand& command) {
  // Every output checked before anything is read or written: none may be
  // the image itself or another output.
  std::vector<OutputFile> outputs;
  if (command.json) outputs.push_back({*command.json, "--json", ".json"});
  if (command.csv) outputs.push_back({*command.csv, "--csv", ".csv"});
  if (command.falseColour) outputs.push_back({*command.falseColour, "--false-colour", ".png"});
  checkOutputFiles(outputs, {command.exr});
  if (command.maxLux && !(std::isfinite(*command.maxLux) && *command.maxLux > 0.0))
    throw UsageError(fmt::format("--max-lux {}: must be a positive number of lux", *command.maxLux));

  ExrContents contents;
  try {
    contents = readExr(command.exr);
  } catch (const ImageIoError& e) {
    throw UsageError(e.what());  // the input, not an output, failed
  }
  const RenderImage& image = contents.image;
  PixelRegion region = wholeImage(image);
  std::vector<float> lux;
  try {
    if (command.region) region = parsePixelRegion(*command.region, image.width, image.height);
    lux = luxGrid(image, region);
  } catch (const MeasureError& e) {
    throw UsageError(fmt::format("{}: {}", command.exr.string(), e.what()));
  }
  const IlluminanceStats stats = illuminanceStats(lux);

  std::fputs(illuminanceText(stats, region).c_str(), stdout);
  if (command.json) writeTextFile(*command.json, illuminanceJson(stats, region), "JSON");
  if (command.csv) writeTextFile(*command.csv, luxCsv(lux, region), "CSV");
  if (command.falseColour) {
    FalseColourScale scale;
    scale.topLux = command.maxLux ? *command.maxLux : legendTop(stats.maxLux);
    const bool topIsOpen = stats.maxLux > scale.topLux;
    const FalseColourImage map = falseColourMap(lux, region, scale, topIsOpen);
    writePngRgb8(*command.falseColour, map.width, map.height, map.rgb);
  }
  return 0;
}

}  // namespace spectrace::cli
