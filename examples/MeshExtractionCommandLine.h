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
#ifndef MeshExtractionCommandLine_h
#define MeshExtractionCommandLine_h

// Small, dependency-free pieces of the meshextraction command-line tool: option
// parsing with per-command declarations and help, number lists, progress output.

#include "itkCommand.h"
#include "itkProcessObject.h"

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace MeshExtractionCLI
{
/** A mistake in how the tool was called: printed with the command's usage, exit 2. */
class UsageError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

struct OptionSpec
{
  std::string name;      ///< without the leading "--"
  std::string valueName; ///< empty for a flag
  std::string help;
  std::string defaultValue;
};

/** A default value as an OptionSpec prints it (shortest form: 10, 0.001, -0.53), for
 * defaults taken from a filter rather than written out again. */
template <typename T>
std::string
DefaultText(T value)
{
  std::ostringstream os;
  os << value;
  return os.str();
}

/** Parsed arguments of one subcommand. */
class Arguments
{
public:
  std::vector<std::string> positional;

  bool
  Has(const std::string & name) const
  {
    return m_Values.count(name) > 0;
  }
  std::string
  Get(const std::string & name, const std::string & fallback = std::string()) const
  {
    const auto found = m_Values.find(name);
    return found == m_Values.end() ? fallback : found->second;
  }
  double
  GetDouble(const std::string & name, double fallback) const
  {
    return Has(name) ? ParseDouble(name, Get(name)) : fallback;
  }
  long
  GetInteger(const std::string & name, long fallback) const
  {
    if (!Has(name))
    {
      return fallback;
    }
    const std::string text = Get(name);
    char *            end = nullptr;
    const long        v = std::strtol(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0')
    {
      throw UsageError("--" + name + " expects an integer, got '" + text + "'");
    }
    return v;
  }
  /** A list of numbers separated by 'x' or ','; a single number is repeated `count` times. */
  std::vector<double>
  GetNumbers(const std::string & name, unsigned int count) const
  {
    std::vector<double> values;
    std::string         text = Get(name);
    for (char & c : text)
    {
      c = (c == 'x' || c == ',') ? ' ' : c;
    }
    std::istringstream in(text);
    std::string        token;
    while (in >> token)
    {
      values.push_back(ParseDouble(name, token));
    }
    if (values.size() == 1 && count > 1)
    {
      values.assign(count, values[0]);
    }
    if (values.size() != count)
    {
      throw UsageError("--" + name + " expects " + std::to_string(count) + " numbers (or one), got '" + Get(name) +
                       "'");
    }
    return values;
  }
  void
  Set(const std::string & name, const std::string & value)
  {
    m_Values[name] = value;
  }

  static double
  ParseDouble(const std::string & name, const std::string & text)
  {
    char *       end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || !std::isfinite(v))
    {
      throw UsageError("--" + name + " expects a number, got '" + text + "'");
    }
    return v;
  }

private:
  std::map<std::string, std::string> m_Values;
};

/** A subcommand: its usage line, description, options and body. */
struct Command
{
  std::string                           name;
  std::string                           summary;
  std::string                           usage;       ///< after "meshextraction <name> "
  std::string                           description; ///< paragraphs shown by --help
  std::vector<OptionSpec>               options;
  std::function<int(const Arguments &)> run;
  unsigned int                          minimumPositional{ 0 };
  unsigned int                          maximumPositional{ 1000 };

  void
  PrintHelp(std::ostream & os) const
  {
    os << "usage: meshextraction " << name << ' ' << usage << "\n\n" << description << "\n";
    if (!options.empty())
    {
      os << "\noptions:\n";
      for (const auto & o : options)
      {
        std::string left = "  --" + o.name + (o.valueName.empty() ? "" : " " + o.valueName);
        os << std::left << std::setw(34) << left << ' ' << o.help;
        if (!o.defaultValue.empty())
        {
          os << " (default: " << o.defaultValue << ")";
        }
        os << '\n';
      }
    }
    os << "  --help                             show this help\n";
  }

  Arguments
  Parse(int argc, char * argv[]) const
  {
    Arguments args;
    for (int i = 0; i < argc; ++i)
    {
      std::string a = argv[i];
      if (a.size() > 2 && a.compare(0, 2, "--") == 0)
      {
        std::string key = a.substr(2);
        std::string value;
        const auto  eq = key.find('=');
        bool        inlineValue = false;
        if (eq != std::string::npos)
        {
          value = key.substr(eq + 1);
          key = key.substr(0, eq);
          inlineValue = true;
        }
        const OptionSpec * spec = nullptr;
        for (const auto & o : options)
        {
          spec = o.name == key ? &o : spec;
        }
        if (spec == nullptr)
        {
          throw UsageError("unknown option --" + key + " for '" + this->name + "'");
        }
        if (!spec->valueName.empty() && !inlineValue)
        {
          if (i + 1 >= argc)
          {
            throw UsageError("--" + key + " needs a value " + spec->valueName);
          }
          value = argv[++i];
        }
        else if (spec->valueName.empty() && inlineValue)
        {
          throw UsageError("--" + key + " takes no value");
        }
        args.Set(key, spec->valueName.empty() ? "1" : value);
      }
      else
      {
        args.positional.push_back(a);
      }
    }
    if (args.positional.size() < minimumPositional || args.positional.size() > maximumPositional)
    {
      throw UsageError("'" + name + "' expects " +
                       (minimumPositional == maximumPositional ? std::to_string(minimumPositional)
                                                               : "at least " + std::to_string(minimumPositional)) +
                       " argument(s), got " + std::to_string(args.positional.size()));
    }
    return args;
  }
};

/** Prints "label: 42%" on stderr as an ITK filter progresses. */
class ProgressPrinter : public itk::Command
{
public:
  using Self = ProgressPrinter;
  using Pointer = itk::SmartPointer<Self>;
  itkNewMacro(Self);

  void
  SetLabel(const std::string & label)
  {
    m_Label = label;
  }
  void
  Execute(itk::Object * caller, const itk::EventObject & event) override
  {
    Execute(static_cast<const itk::Object *>(caller), event);
  }
  void
  Execute(const itk::Object * caller, const itk::EventObject & event) override
  {
    const auto * process = dynamic_cast<const itk::ProcessObject *>(caller);
    if (process == nullptr)
    {
      return;
    }
    if (itk::ProgressEvent().CheckEvent(&event))
    {
      const int percent = static_cast<int>(100.0f * process->GetProgress());
      if (percent >= m_Last + 10 || (percent == 100 && m_Last != 100))
      {
        m_Last = percent;
        std::cerr << "  " << m_Label << ": " << percent << "%\n";
      }
    }
  }

private:
  std::string m_Label{ "progress" };
  int         m_Last{ -10 };
};

template <typename TFilter>
void
ReportProgress(TFilter * filter, const std::string & label)
{
  auto printer = ProgressPrinter::New();
  printer->SetLabel(label);
  filter->AddObserver(itk::ProgressEvent(), printer);
}

/** Wall-clock timer for messages on stderr. */
class Stopwatch
{
public:
  double
  Seconds() const
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - m_Start).count();
  }

private:
  std::chrono::steady_clock::time_point m_Start{ std::chrono::steady_clock::now() };
};

} // namespace MeshExtractionCLI

#endif
