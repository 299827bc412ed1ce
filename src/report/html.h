// HTML building blocks of the report: the page skeleton with its inline CSS
// (screen and print), figures, tables and the number formats the tables use.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace mpcal::report {

/// <!DOCTYPE html> … <body>, with the whole stylesheet inline.
std::string PageBegin(std::string_view title);
/// </body></html>
std::string PageEnd();

/// A numbered figure: the SVG and a caption (plain text, escaped here).
std::string Figure(const std::string& svg, std::string_view caption);

/// A table built row by row; every cell is plain text, escaped here.
class Table {
 public:
  explicit Table(std::string_view css_class = "");
  void Header(const std::vector<std::string>& cells);
  void Row(const std::vector<std::string>& cells, std::string_view row_class = "");
  std::string Finish();

 private:
  std::string html_;
  bool body_open_ = false;
};

/// "value ± sigma" with sigma to two significant digits and the value to the
/// same decimal place; the value alone (`significant` digits) without sigma.
std::string PlusMinus(double value, std::optional<double> sigma, int significant = 4);

/// `v` with `significant` significant digits, fixed notation when readable.
std::string Significant(double v, int significant = 4);

/// `v` with `decimals` decimals. These formats give "—" for a value that is
/// not finite: no cell of the report reads inf or nan.
std::string Fixed(double v, int decimals);

/// A paragraph (escaped).
std::string Paragraph(std::string_view text, std::string_view css_class = "");

/// The warnings as a highlighted list, or "No warnings." in a quiet box.
std::string WarningsList(const std::vector<std::string>& warnings);

}  // namespace mpcal::report
