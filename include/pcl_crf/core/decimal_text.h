#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace pcl_crf
{

/** \brief Numbers in the text files pcl_crf reads and writes (datasets, models, logs,
 *  predictions, reports), the same whatever the C or C++ locale of the program.
 *
 *  strtod, printf and iostreams follow the program's locale: in a host program that
 *  called setlocale (LC_ALL, "") under a German locale, strtod stops "0.25" at its point
 *  and printf writes "0,25", so the shipped models and datasets would not load and the
 *  files written would not read elsewhere. These use std::from_chars and std::to_chars,
 *  which always use the point.
 *
 *  \code
 *  const std::optional<double> x = pcl_crf::parseDecimal ("-1.5e-3");  // -0.0015
 *  const std::string text = pcl_crf::formatGeneral (0.25, 17);        // "0.25"
 *  \endcode
 */

/** \brief Reads the whole of \a text as a finite decimal number ("0.25", "-1e-3", "+2",
 *  ".5"). Refuses hexadecimal ("0x10", which strtod reads as 16), "inf", "nan", spaces,
 *  a decimal comma, trailing characters and numbers too large for a double; one too
 *  small for it reads as 0 or a subnormal ("1e-400" is 0), as strtod rounds it.
 *  \return the number, or std::nullopt when \a text is not one */
std::optional<double>
parseDecimal (std::string_view text);

/** \brief parseDecimal () for a float, rounded once from the text (as a PCD file's
 *  TYPE F SIZE 4 field is read). \return std::nullopt as well beyond a float's range */
std::optional<float>
parseDecimalFloat (std::string_view text);

/** \brief \a value as printf's "%.<significant>g" writes it in the C locale ("0.25",
 *  "1.0000000000000001e-09" for 1e-9 with 17 digits, which read back exactly). */
std::string
formatGeneral (double value, int significant);

/** \brief \a value as printf's "%.<decimals>f" writes it in the C locale ("0.8665"). */
std::string
formatFixed (double value, int decimals);

/** \brief \a value as printf's "%.<decimals>e" writes it in the C locale ("1.230e-04"). */
std::string
formatScientific (double value, int decimals);

/** \brief The shortest text that parseDecimal () reads back as exactly \a value
 *  ("0.1", "-1", "1e-09"). */
std::string
formatShortest (double value);

}  // namespace pcl_crf
