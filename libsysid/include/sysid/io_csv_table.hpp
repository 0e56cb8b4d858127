// The one writer of CSV tables: the report's tables, the CLI's (dominance, compare's summary,
// simulate's events, export's vectors) and Python's, in one dialect.
#ifndef SYSID_IO_CSV_TABLE_HPP_
#define SYSID_IO_CSV_TABLE_HPP_

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace sysid {

/// `s` as one field of a CSV table (RFC 4180): quoted, inner quotes doubled, when it holds a
/// comma, a double quote, a carriage return or a line feed (a file name may), else unchanged.
std::string CsvField(std::string_view s);

/// A CSV table as RFC 4180 reads it, with LF line ends (RFC 4180 names CRLF; every reader
/// takes LF, and sysid's tables always had it): a header row, then rows of exactly as many
/// fields. Text fields follow CsvField; numbers are written as given by their method, so a
/// table's bytes are fixed by its code. Lines before the header (`preamble`: the generator
/// mark, "# ..." comments) are the caller's and written as given. A row with another number
/// of fields than the header is a programming error (SYSID_CHECK). docs/recordings.md, "CSV
/// tables".
///
///   CsvTable t({"source", "rms_mps"});
///   t.Text("a,b.csv").Number(0.5).EndRow();   // "source,rms_mps\n\"a,b.csv\",0.5\n"
class CsvTable {
 public:
  explicit CsvTable(const std::vector<std::string>& header, std::string_view preamble = "");

  /// A text field, quoted only when it must be (CsvField).
  CsvTable& Text(std::string_view field);
  /// A text field always in quotes, inner quotes doubled: for columns whose files always
  /// quoted it (the same value to any RFC 4180 reader).
  CsvTable& Quoted(std::string_view field);
  /// `v` with `significant_digits` significant digits, printf's %.{N}g ("nan", "inf" as
  /// printf writes them). 17 digits read back to the same double.
  CsvTable& Number(double v, int significant_digits = 9);
  /// The shortest text that reads back to `v` (fmt's "{}").
  CsvTable& Shortest(double v);
  CsvTable& Integer(long long v);
  /// An empty field (a column that does not apply to this row).
  CsvTable& Empty();
  /// Ends the row; it must hold as many fields as the header.
  CsvTable& EndRow();

  std::size_t rows() const { return rows_; }
  /// The table's text; every row must be ended.
  const std::string& str() const;

 private:
  CsvTable& Append(std::string_view raw);

  std::string text_;
  std::size_t columns_ = 0;
  std::size_t fields_ = 0;  ///< in the row being written
  std::size_t rows_ = 0;    ///< ended, the header not counted
};

}  // namespace sysid

#endif  // SYSID_IO_CSV_TABLE_HPP_
