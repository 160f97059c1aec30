#!/bin/bash
# The layering rules of issue 15, checked on the sources so that they stay true:
#  - the logic names its settings, never a front end's flags;
#  - the logic includes nothing of the widgets, the module or the phantom generators;
#  - a command's Run...Command is called only from the command table;
#  - no front end captures stdout (the CLI harness's stderr-to-stdout for Slicer aside);
#  - a command's parser, --help and (for Slicer) XML come from its one description;
#  - commands take their logic and overlays from the module class, as Slicer's widgets do;
#  - Logic's folders are layers (issue 30): a folder includes only folders of lower layers, never
#    one beside it or above it, and every folder has its layer;
#  - the front ends (Module/, Widgets/) include only Logic's public headers (Logic/PublicHeaders.txt);
#    the phantom generators (Phantom/) too, and nothing of Module/, Widgets/ or Benchmark/; the
#    benchmarks (Benchmark/) Logic's public headers and the internals they measure
#    (Benchmark/MeasuredHeaders.txt), nothing of Module/ or Widgets/ (issue 51);
#  - the VesselProximity module includes nothing of Phantom/ or Benchmark/: the demo module
#    (Module/Demo) alone does (issue 51);
#  - no two classes use each other: where A's files include B's header, B's files do not include
#    A's (issue 51), but for a header that builds on another class's types for that class's own
#    implementation (a pimpl's Internals, a parser's value helpers: B.h includes A.h, A.cxx B.h).
# Prints each breach as file:line and exits 1 when there is one.
set -u
root="${1:?usage: CheckLayering.sh SOURCE_DIR}"
cd "$root" || exit 2
failed=0
breach() {
  if [ -n "$2" ]; then
    echo "$1:"
    echo "$2"
    failed=1
  fi
}
breach "command-line flag text in Logic/ (name the parameter: vp::ParameterError)" \
  "$(grep -rnE --include='*.h' --include='*.cxx' '"([^"\\]|\\.)*--[a-z]' Logic | grep -vE '^[^:]+:[0-9]+: *//')"

# Logic's layers, lowest first; the folders of one line are independent of each other.
layers=(
  "Common"
  "Mesh Segmentation Registration ZBuffer/Vulkan"
  "Engine Scalpel Models"
  "ExactEngine"
  "ZBuffer"
  "Instrument"
  "Tumour"
  "Tracking"
  "Reports Audio"
  "Live"
  "."
  "Cohort Planning"
)
layer_of() {
  local rank=0 line folder
  for line in "${layers[@]}"; do
    for folder in $line; do
      [ "$folder" = "$1" ] && { echo "$rank"; return; }
    done
    rank=$((rank + 1))
  done
  echo -1
}
declare -A header_folder
while IFS= read -r f; do
  folder=$(dirname "${f#Logic/}")
  header_folder[$(basename "$f")]=$folder
done < <(find Logic -name '*.h' | sort)
unplaced=""
wrong_way=""
while IFS= read -r folder; do
  [ "$folder" = Logic ] && folder=. || folder=${folder#Logic/}
  [ "$(layer_of "$folder")" = -1 ] && unplaced+="Logic/$folder"$'\n'
done < <(find Logic -type f \( -name '*.h' -o -name '*.cxx' \) -printf '%h\n' | sort -u)
while IFS=: read -r file line text; do
  included=${text#*#include \"}; included=${included%%\"*}
  target=${header_folder[$(basename "$included")]:-}
  [ -n "$target" ] || continue
  source=${file#Logic/}; [[ "$source" == */* ]] && source=${source%/*} || source=.
  [ "$source" = "$target" ] && continue
  from=$(layer_of "$source"); to=$(layer_of "$target")
  if [ "$from" -le "$to" ]; then
    wrong_way+="$file:$line: Logic/$source (layer $from) includes $included of Logic/$target (layer $to)"$'\n'
  fi
done < <(grep -rnE --include='*.h' --include='*.cxx' '^#include "' Logic)
breach "a Logic folder with no layer (add it to the layers in Testing/CheckLayering.sh)" "${unplaced%$'\n'}"
breach "a Logic folder includes one of its own layer or above (a circle, or a wrong-way include)" "${wrong_way%$'\n'}"
breach "Logic/ includes a widget, module or phantom header" \
  "$(grep -rnE --include='*.h' --include='*.cxx' '#include "(vtkVesselProximityView|vtkVesselProximityOverlays|vpCommand|vpCli|vpLiverPhantom|vpDemoTrajectory|vpAnalyticShapes|vpBuiltInPhantom|vpCusaHandpiece|vpMeshRefinement)' Logic)"
breach "Run...Command called outside the command table" \
  "$(grep -rnE --include='*.h' --include='*.cxx' '\bRun[A-Z][A-Za-z]*Command\(' Module Widgets Logic Phantom |
     grep -vE '^Module/Commands/vpCommandTable\.cxx:|^Module/Commands/vpCommands\.h:|^Module/Demo/vpDemoCommandTable\.cxx:|^Module/Demo/vpDemoCommands\.h:|^Module/(Commands|Demo)/vp[A-Za-z]+Command\.cxx:[0-9]+:int Run')"
breach "stdout captured outside the CLI harness" \
  "$(grep -rn --include='*.h' --include='*.cxx' 'cout.rdbuf\|cout\.rdbuf(' Module Widgets Logic Phantom | grep -v '^Module/CLI/vpCliProgram\.cxx:')"
breach "a command's usage or options written by hand (declare them in its description: vpCliDescription.h)" \
  "$(grep -rnE --include='*.h' --include='*.cxx' 'const char\* *Usage|std::set<std::string> options|Arguments args\(' Module/Commands Module/Demo)"
breach "a command makes its own logic or overlays (take them from the module: ModuleServices; vpModuleServices.cxx is where the modules make them)" \
  "$(grep -rnE --include='*.h' --include='*.cxx' 'vtkVesselProximity(Logic|Overlays)>::New|vtkNew<vtkVesselProximity(Logic|Overlays)>' Module/Commands Module/Demo |
     grep -v '^Module/Commands/vpModuleServices\.cxx:')"
public=" $(grep -vE '^\s*(#|$)' Logic/PublicHeaders.txt | tr '\n' ' ') "
private_use=""
while IFS=: read -r file line text; do
  included=${text#*#include \"}; included=${included%%\"*}; included=${included##*/}
  [ -n "${header_folder[$included]:-}" ] || continue
  [[ "$public" == *" $included "* ]] || private_use+="$file:$line: $included"$'\n'
done < <(grep -rnE --include='*.h' --include='*.cxx' '^#include "' Module Widgets)
breach "a front end includes a header Logic/PublicHeaders.txt does not list" "${private_use%$'\n'}"
stale=""
for listed in $public; do
  [ -n "${header_folder[$listed]:-}" ] || stale+="Logic/PublicHeaders.txt: $listed"$'\n'
done
breach "a public header that is not in Logic/" "${stale%$'\n'}"
for part in Phantom Benchmark; do
  allowed="$public"
  [ "$part" = Benchmark ] && allowed+=" $(grep -vE '^\s*(#|$)' Benchmark/MeasuredHeaders.txt | tr '\n' ' ') "
  reach=""
  while IFS=: read -r file line text; do
    included=${text#*#include \"}; included=${included%%\"*}; included=${included##*/}
    [ -n "${header_folder[$included]:-}" ] || continue
    [[ "$allowed" == *" $included "* ]] || reach+="$file:$line: $included"$'\n'
  done < <(grep -rnE --include='*.h' --include='*.cxx' '^#include "' "$part")
  breach "$part/ includes a Logic header that is neither public nor listed for it" "${reach%$'\n'}"
done
headers_of() { find "$@" -name '*.h' -printf '%f|' | sed -e 's/|$//' -e 's/\./\\./g'; }
breach "Benchmark/ includes a header of a front end" \
  "$(grep -rnE --include='*.h' --include='*.cxx' "^#include \"($(headers_of Module Widgets))\"" Benchmark)"
breach "Phantom/ includes a header of a front end or a benchmark" \
  "$(grep -rnE --include='*.h' --include='*.cxx' "^#include \"($(headers_of Module Widgets Benchmark))\"" Phantom)"
breach "the VesselProximity module (Module/ but its Demo/ module) includes a phantom or benchmark header" \
  "$(grep -rnE --include='*.h' --include='*.cxx' "^#include \"($(headers_of Phantom Benchmark))\"" Module --exclude-dir=Demo)"
breach "Logic/ includes a benchmark header" \
  "$(grep -rnE --include='*.h' --include='*.cxx' "^#include \"($(headers_of Benchmark))\"" Logic)"
# Which class's files include which class's header: "A>B" is A's header or implementation
# including B's header; a header's own inclusion is noted apart (A.h includes B.h).
declare -A uses=() header_uses=()
while IFS=: read -r file line text; do
  included=${text#*#include \"}; included=${included%%\"*}; included=${included##*/}
  a=${file##*/}; a=${a%.*}; b=${included%.h}
  [ "$a" = "$b" ] && continue
  uses["$a>$b"]="$file:$line"
  [[ "$file" == *.h ]] && header_uses["$a>$b"]=1
done < <(grep -rnE --include='*.h' --include='*.cxx' '^#include "[^"]+\.h"' Logic Widgets Module Benchmark Phantom)
mutual=""
for key in "${!uses[@]}"; do
  a=${key%>*}; b=${key#*>}
  [[ "$a" < "$b" ]] && [ -n "${uses[$b>$a]:-}" ] || continue
  # B.h builds on A's types for A's implementation (or the other way): one direction per side.
  [ -n "${header_uses[$b>$a]:-}" ] && [ -z "${header_uses[$a>$b]:-}" ] && continue
  [ -n "${header_uses[$a>$b]:-}" ] && [ -z "${header_uses[$b>$a]:-}" ] && continue
  mutual+="${uses[$key]} and ${uses[$b>$a]}: $a and $b include each other"$'\n'
done
breach "two classes include each other (give one an interface the other implements)" "${mutual%$'\n'}"
[ "$failed" = 0 ] && echo "layering: every rule holds"
exit "$failed"
