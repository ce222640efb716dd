// SPDX-License-Identifier: GPL-3.0-or-later
// `sonargrid-cli convert`: read a log of any supported format and write it as .sglog or CARMEN
// (docs/cli.md, "convert").

#include <iostream>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "map_options.h"
#include "sonargrid/io/carmen.h"
#include "sonargrid/io/sglog.h"

namespace sg::cli {
namespace {

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// --to, or the extension of --out.
std::string outputFormat(const std::optional<std::string>& to, const std::string& out) {
  if (to) {
    if (*to != "sglog" && *to != "carmen") {
      throw UsageError("--to takes sglog or carmen, got '" + *to + "'");
    }
    return *to;
  }
  if (endsWith(out, ".sglog")) return "sglog";
  if (endsWith(out, ".clf") || endsWith(out, ".carmen")) return "carmen";
  throw UsageError("cannot tell the output format from '" + out +
                   "' (.sglog, .clf or .carmen); give --to sglog or --to carmen");
}

}  // namespace

int runConvert(Arguments& args) {
  const std::string in = args.required("--in");
  const LogOptions read = parseLogOptions(args);
  const std::string out = args.required("--out");
  const auto to = args.value("--to");
  const bool json = args.flag("--json");
  args.finish();
  const std::string format = outputFormat(to, out);

  LoadReport report;
  const Dataset data = loadLog(in, read, &report);
  if (format == "sglog") {
    writeSglog(data, out);
  } else {
    writeCarmen(data, out);
  }

  if (json) {
    nlohmann::ordered_json o;
    o["in"] = in;
    o["in_format"] = std::string(logFormatName(report.format));
    o["out"] = out;
    o["out_format"] = format;
    o["scans"] = data.scans.size();
    o["readings"] = data.readingCount();
    o["sonars"] = data.ring.size();
    o["lines"] = report.lines;
    o["skipped_lines"] = report.skippedLines;
    nlohmann::ordered_json ignored = nlohmann::ordered_json::object();
    for (const auto& [type, count] : report.ignoredMessages) ignored[type] = count;
    o["ignored_messages"] = ignored;
    std::cout << o.dump() << '\n';
  } else {
    std::cout << in << " (" << logFormatName(report.format) << "): " << data.scans.size()
              << " scans, " << data.readingCount() << " readings of " << data.ring.size()
              << " sonars\n";
    if (!report.ignoredMessages.empty()) {
      std::cout << "  messages not used:";
      for (const auto& [type, count] : report.ignoredMessages) {
        std::cout << ' ' << type << " ×" << count << ';';
      }
      std::cout << '\n';
    }
    std::cout << "wrote " << out << " (" << format << ")\n";
  }
  return 0;
}

}  // namespace sg::cli
