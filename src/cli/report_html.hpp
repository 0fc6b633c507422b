#pragma once
/// \file report_html.hpp  The reproduction report (index.html): our numbers beside the thesis's
/// and the paper's, and every figure, read from the run directories `flexgait reproduce` wrote.
#include <filesystem>
#include <string>
#include <vector>

namespace flexgait::cli {

struct ReportSection {
  std::string dir;      ///< run directory, relative to the report
  std::string title;
  std::string command;  ///< the command that made it (shown)
  int exit_code = 0;
};

/// index.html's text for the runs under `root`.
std::string reproduction_report(const std::filesystem::path& root, const std::vector<ReportSection>& sections,
                                bool quick);

}  // namespace flexgait::cli
