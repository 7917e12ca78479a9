#include <pcl_crf/core/decimal_text.h>

#include <charconv>
#include <cmath>
#include <system_error>

namespace pcl_crf
{

namespace
{

/** Room for any double in any of the formats below (17 significant digits, a sign, a
 *  point, an exponent; 308 integer digits and the decimals for "%f"). */
constexpr std::size_t kBufferSize = 400;

std::string
formatted (double value, std::chars_format format, int precision)
{
  char buffer[kBufferSize];
  const std::to_chars_result result = std::to_chars (buffer, buffer + kBufferSize, value, format, precision);
  if (result.ec != std::errc ())
    return std::string ("?");  // unreachable with kBufferSize and the precisions used
  return std::string (buffer, result.ptr);
}

/** A decimal number std::from_chars found out of \a Real's range: the nearest \a Real (0
 *  or a subnormal, signed) when it is too small in magnitude (as strtod rounds it),
 *  nothing when it is too large. Told by a long double, whose range is wider, and
 *  beyond that by the sign of the exponent. */
template <typename Real>
std::optional<Real>
underflowed (std::string_view text)
{
  long double wide = 0;
  const char* end = text.data () + text.size ();
  const std::from_chars_result result = std::from_chars (text.data (), end, wide, std::chars_format::general);
  if (result.ec == std::errc () && result.ptr == end)
    return std::abs (wide) < 1 ? std::optional<Real> (static_cast<Real> (wide)) : std::nullopt;
  const std::size_t exponent = text.find_first_of ("eE");
  if (exponent == std::string_view::npos || exponent + 1 >= text.size () || text[exponent + 1] != '-')
    return std::nullopt;
  return text.front () == '-' ? -Real (0) : Real (0);
}

/** parseDecimal () into \a Real, rounded once (a float read through a double may round twice). */
template <typename Real>
std::optional<Real>
parseDecimalAs (std::string_view text)
{
  if (!text.empty () && text.front () == '+') {  // strtod takes it, std::from_chars does not
    text.remove_prefix (1);
    if (!text.empty () && (text.front () == '-' || text.front () == '+'))
      return std::nullopt;
  }
  Real value = 0;
  const char* end = text.data () + text.size ();
  const std::from_chars_result result = std::from_chars (text.data (), end, value, std::chars_format::general);
  if (!text.empty () && result.ec == std::errc::result_out_of_range && result.ptr == end)
    return underflowed<Real> (text);
  if (text.empty () || result.ec != std::errc () || result.ptr != end || !std::isfinite (value))
    return std::nullopt;
  return value;
}

}  // namespace

std::optional<double>
parseDecimal (std::string_view text)
{
  return parseDecimalAs<double> (text);
}

std::optional<float>
parseDecimalFloat (std::string_view text)
{
  return parseDecimalAs<float> (text);
}

std::string
formatGeneral (double value, int significant)
{
  return formatted (value, std::chars_format::general, significant);
}

std::string
formatFixed (double value, int decimals)
{
  return formatted (value, std::chars_format::fixed, decimals);
}

std::string
formatScientific (double value, int decimals)
{
  return formatted (value, std::chars_format::scientific, decimals);
}

std::string
formatShortest (double value)
{
  char buffer[kBufferSize];
  const std::to_chars_result result = std::to_chars (buffer, buffer + kBufferSize, value);
  return std::string (buffer, result.ptr);
}

}  // namespace pcl_crf
