#pragma once
// Cells of the CSV files a TA opens in a spreadsheet (a class batch's summary.csv and
// explanations.csv), where every student name and message is a stranger's text.
#include <string>
#include <string_view>

namespace shadelab {

// One RFC 4180 cell: quoted (its quotes doubled) when it holds a comma, a quote, CR or LF, so a
// folder named "zoe\ralice" stays one cell of one row; and a cell a spreadsheet would read as a
// formula (it begins with =, +, -, @, a tab or CR) is prefixed with ' (OWASP's advice) so it is
// shown, never evaluated.
std::string csv_cell(std::string_view text);

// `text` with every control character (C0, DEL, C1 in UTF-8) written as \xNN, so a name shown in a
// terminal, a results file or a CSV cannot move the cursor, hide lines or start a new row.
std::string printable(std::string_view text);
// The same, keeping LF and tab: text of several lines (a grader's output shown in PrairieLearn,
// whose ansi2html would style an escape code a file name carried).
std::string printable_lines(std::string_view text);

}  // namespace shadelab
