/*=========================================================================
 *
 *  Copyright NumFOCUS
 *
 *  Licensed under the Apache License, Version 2.0 (the "License");
 *  you may not use this file except in compliance with the License.
 *  You may obtain a copy of the License at
 *
 *         https://www.apache.org/licenses/LICENSE-2.0.txt
 *
 *  Unless required by applicable law or agreed to in writing, software
 *  distributed under the License is distributed on an "AS IS" BASIS,
 *  WITHOUT WARRANTIES OR CONDITIONS OF ANY KIND, either express or implied.
 *  See the License for the specific language governing permissions and
 *  limitations under the License.
 *
 *=========================================================================*/
// Option parsing with per-command declarations and help.

#include "MeshExtractionCLI.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>
#include <utility>
#include <vector>

namespace MeshExtractionCLI
{
// ------------------------------------------------------------------------------
// Arguments
// ------------------------------------------------------------------------------
namespace
{
/** The numbers of an option's value, each as written and as parsed: a list separated by
 * 'x' (a size: 64x64x32; no number has an 'x' of its own) or ','. */
std::vector<std::pair<std::string, double>>
ListedNumbers(const std::string & name, std::string text)
{
  for (char & c : text)
  {
    c = (c == 'x' || c == ',') ? ' ' : c;
  }
  std::vector<std::pair<std::string, double>> numbers;
  std::istringstream                          in(text);
  std::string                                 token;
  while (in >> token)
  {
    numbers.emplace_back(token, Arguments::ParseDouble(name, token));
  }
  return numbers;
}
} // namespace

bool
Arguments::Has(const std::string & name) const
{
  return m_Values.count(name) > 0;
}

std::string
Arguments::Get(const std::string & name, const std::string & fallback) const
{
  const auto found = m_Values.find(name);
  return found == m_Values.end() ? fallback : found->second;
}

double
Arguments::GetDouble(const std::string & name, double fallback) const
{
  return Has(name) ? ParseDouble(name, Get(name)) : fallback;
}

long
Arguments::GetInteger(const std::string & name, long fallback) const
{
  if (!Has(name))
  {
    return fallback;
  }
  const std::string text = Get(name);
  char *            end = nullptr;
  errno = 0;
  const long v = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0')
  {
    throw UsageError("--" + name + " expects an integer, got '" + text + "'");
  }
  // Options count voxels, iterations, threads: none of them is near 2^31, and a value
  // cast to a narrower type must not wrap around silently.
  if (errno == ERANGE || v > std::numeric_limits<int>::max() || v < std::numeric_limits<int>::min())
  {
    throw UsageError("--" + name + " is out of range: '" + text + "'");
  }
  return v;
}

std::vector<double>
Arguments::GetNumbers(const std::string & name, unsigned int count) const
{
  std::vector<double> values;
  for (const auto & number : ListedNumbers(name, Get(name)))
  {
    values.push_back(number.second);
  }
  if (values.size() == 1 && count > 1)
  {
    values.assign(count, values[0]);
  }
  if (values.size() != count)
  {
    throw UsageError("--" + name + " expects " + std::to_string(count) + " numbers (or one), got '" + Get(name) + "'");
  }
  return values;
}

void
Arguments::Set(const std::string & name, const std::string & value)
{
  m_Values[name] = value;
}

double
Arguments::ParseDouble(const std::string & name, const std::string & text)
{
  char *       end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(v))
  {
    throw UsageError("--" + name + " expects a number, got '" + text + "'");
  }
  return v;
}

// ------------------------------------------------------------------------------
// OptionRange
// ------------------------------------------------------------------------------
OptionRange
OptionRange::Between(double low, double high)
{
  OptionRange r;
  r.minimum = low;
  r.maximum = high;
  return r;
}

OptionRange
OptionRange::Inside(double low, double high)
{
  OptionRange r = Between(low, high);
  r.minimumExcluded = true;
  r.maximumExcluded = true;
  return r;
}

OptionRange
OptionRange::AboveUpTo(double low, double high)
{
  OptionRange r = Between(low, high);
  r.minimumExcluded = true;
  return r;
}

OptionRange
OptionRange::Any()
{
  OptionRange r;
  r.minimumExcluded = true; // of -infinity: any finite number
  return r;
}

bool
OptionRange::IsSet() const
{
  return std::isfinite(minimum) || std::isfinite(maximum) || minimumExcluded;
}

bool
OptionRange::Contains(double value) const
{
  return std::isfinite(value) && (minimumExcluded ? value > minimum : value >= minimum) &&
         (maximumExcluded ? value < maximum : value <= maximum);
}

std::string
OptionRange::Text() const
{
  if (!std::isfinite(minimum) && !std::isfinite(maximum))
  {
    return "any number";
  }
  const auto number = [](double v) {
    std::ostringstream os;
    os << v;
    return os.str();
  };
  if (!std::isfinite(maximum))
  {
    return (minimumExcluded ? "> " : ">= ") + number(minimum);
  }
  return (minimumExcluded ? "(" : "[") + number(minimum) + ", " + number(maximum) + (maximumExcluded ? ")" : "]");
}

namespace
{
/** A UsageError naming the range unless every number of `value` (a list separated by
 * 'x' or ',' for list options) is in the option's range. */
void
CheckRange(const OptionSpec & spec, const std::string & value)
{
  const auto numbers = ListedNumbers(spec.name, value);
  for (const auto & [text, number] : numbers)
  {
    if (!spec.range.Contains(number))
    {
      throw UsageError("--" + spec.name + " must be in " + spec.range.Text() + ", got " + text);
    }
  }
  if (numbers.empty())
  {
    throw UsageError("--" + spec.name + " expects a number, got '" + value + "'");
  }
}
} // namespace

// ------------------------------------------------------------------------------
// Command
// ------------------------------------------------------------------------------
void
Command::PrintHelp(std::ostream & os) const
{
  os << "usage: meshextraction " << name << ' ' << usage << "\n\n" << description << "\n";
  if (!options.empty())
  {
    os << "\noptions:\n";
    for (const auto & o : options)
    {
      std::string left = "  --" + o.name + (o.valueName.empty() ? "" : " " + o.valueName);
      os << std::left << std::setw(34) << left << ' ' << o.help;
      if (o.range.IsSet())
      {
        os << " (" << o.range.Text() << (o.defaultValue.empty() ? ")" : "; default: " + o.defaultValue + ")");
      }
      else if (!o.defaultValue.empty())
      {
        os << " (default: " << o.defaultValue << ")";
      }
      os << '\n';
    }
  }
  os << "  --help                             show this help\n";
}

namespace
{
/** Whether an argument is an option ("--name" or "--name=value"). */
bool
IsOption(const std::string & argument)
{
  return argument.size() > 2 && argument.compare(0, 2, "--") == 0;
}

/** The declaration of option --key of `command`; a UsageError if it has none. */
const OptionSpec &
FindOption(const Command & command, const std::string & key)
{
  const OptionSpec * spec = nullptr;
  for (const auto & o : command.options)
  {
    spec = o.name == key ? &o : spec;
  }
  if (spec == nullptr)
  {
    throw UsageError("unknown option --" + key + " for '" + command.name + "'");
  }
  return *spec;
}

/** Records the option argv[i] (with its value: after '=' or the next argument) in
 * `args`; returns the index of the last argument it used. */
int
ParseOption(const Command & command, int argc, char * argv[], int i, Arguments & args)
{
  std::string key = std::string(argv[i]).substr(2);
  std::string value;
  const auto  eq = key.find('=');
  bool        inlineValue = false;
  if (eq != std::string::npos)
  {
    value = key.substr(eq + 1);
    key = key.substr(0, eq);
    inlineValue = true;
  }
  const OptionSpec & spec = FindOption(command, key);
  if (!spec.valueName.empty() && !inlineValue)
  {
    if (i + 1 >= argc)
    {
      throw UsageError("--" + key + " needs a value " + spec.valueName);
    }
    value = argv[++i];
  }
  else if (spec.valueName.empty() && inlineValue)
  {
    throw UsageError("--" + key + " takes no value");
  }
  if (spec.range.IsSet())
  {
    CheckRange(spec, value);
  }
  args.Set(key, spec.valueName.empty() ? "1" : value);
  return i;
}

/** A UsageError unless the command got between its minimum and maximum number of
 * positional arguments. */
void
CheckNumberOfPositional(const Command & command, const Arguments & args)
{
  const unsigned int minimum = command.minimumPositional;
  const unsigned int maximum = command.maximumPositional;
  const std::size_t  got = args.positional.size();
  if (got >= minimum && got <= maximum)
  {
    return;
  }
  std::string expected = minimum == maximum ? std::to_string(minimum) : "at least " + std::to_string(minimum);
  if (got > maximum && minimum != maximum)
  {
    expected = std::to_string(minimum) + " to " + std::to_string(maximum);
  }
  std::string message = "'" + command.name + "' expects " + expected + " argument(s), got " + std::to_string(got);
  if (got > maximum)
  {
    // The usual cause: an option's list written with spaces.
    message += " (the first surplus one is '" + args.positional[maximum] +
               "'; an option takes one value: write lists with commas, e.g. --direction 1,0,0,0,1,0,0,0,1)";
  }
  throw UsageError(message);
}
} // namespace

Arguments
Command::Parse(int argc, char * argv[]) const
{
  Arguments args;
  for (int i = 0; i < argc; ++i)
  {
    if (IsOption(argv[i]))
    {
      i = ParseOption(*this, argc, argv, i, args);
    }
    else
    {
      args.positional.push_back(argv[i]);
    }
  }
  CheckNumberOfPositional(*this, args);
  return args;
}

} // namespace MeshExtractionCLI
