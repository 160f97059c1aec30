#!/bin/bash
# The installed tree stands alone: `cmake --install` into a prefix, the prefix then moved (so no
# path written at install time can be relied on), its CLI modules, host and module run from an
# unrelated folder, no library loaded from the build tree (ld.so's own account), every RUNPATH
# relative; then a consumer project finds the package and links the logic.
#   TestInstalledTree.sh BUILD_DIR CONSUMER_SOURCE WORK_DIR
set -euo pipefail
build=$(cd "$1" && pwd) consumer=$(cd "$2" && pwd) work=$3
rm -rf "$work"
mkdir -p "$work/elsewhere"
fail() { echo "InstalledTree: $*" >&2; exit 1; }

cmake --install "$build" --prefix "$work/prefix" > "$work/install.log"
# A space and non-ASCII letters; no comma: a linker's -Wl,-rpath,DIR cannot carry one, so no C++
# project could link from such a prefix, ours or any other.
moved="$work/moved prefix Überprüfung"
mv "$work/prefix" "$moved"
slicer=$(ls -d "$moved"/lib/Slicer-*)
cli="$slicer/cli-modules"
for f in "$cli/VesselProximityModels" "$cli/VesselProximityDistance" "$cli/VesselProximityTrack" \
  "$slicer/vesselproximity-modules/libVesselProximityModule.so" "$slicer/qt-loadable-modules/libVesselProximityLogic.so" \
  "$slicer/vesselproximity-modules/libVesselProximityDemoModule.so" "$slicer/qt-loadable-modules/libVesselProximityCommands.so" \
  "$slicer/VesselProximity.s4ext" \
  "$slicer/qt-loadable-modules/libVesselProximityWidgets.so" "$slicer/qt-loadable-modules/libVesselProximityPhantom.so" \
  "$moved/bin/vesselproximity" "$moved/include/VesselProximity/vtkVesselProximityLogic.h" \
  "$moved/lib/cmake/VesselProximity/VesselProximityConfig.cmake" "$moved/share/doc/VesselProximity/README.md" \
  "$moved/share/doc/VesselProximity/Documentation/UserGuide.md" \
  "$moved/share/doc/VesselProximity/Resources/Documentation/demo_breach.png"; do
  [ -e "$f" ] || fail "not installed: ${f#$moved/}"
done

# Every RUNPATH of ours is $ORIGIN-relative or a system folder, never the build tree.
# Slicer loads every *Module library of qt-loadable-modules as a Qt plugin: ours are not, so none is there.
if ls "$slicer"/qt-loadable-modules/*Module.so > /dev/null 2>&1; then
  fail "a module library in qt-loadable-modules, where Slicer would load it as a Qt plugin: $(ls "$slicer"/qt-loadable-modules/*Module.so)"
fi
for f in "$cli"/* "$slicer"/qt-loadable-modules/*.so "$slicer"/vesselproximity-modules/*.so "$moved/bin/vesselproximity"; do
  runpath=$(readelf -d "$f" | sed -n 's/.*(RUNPATH).*\[\(.*\)\]/\1/p')
  case "${runpath//$work/}" in *"$build"*) fail "${f#$moved/} has the build tree in its RUNPATH: $runpath" ;; esac
done

cd "$work/elsewhere"
# The host finds its module in the installed layout; the phantom gives vessels to measure.
LD_DEBUG=libs "$moved/bin/vesselproximity" phantom -o phantom > phantom.out 2> phantom.ld || fail "host: $(tail -3 phantom.ld)"
[ -f phantom/portal_vein.stl ] || fail "host: the phantom was not written"
params="$work/elsewhere/distance.params"
LD_DEBUG=libs "$cli/VesselProximityDistance" --returnparameterfile "$params" --portalVein phantom/portal_vein.stl \
  --tip 30,0,10 > distance.out 2> distance.ld || fail "VesselProximityDistance: $(grep -v '^ *[0-9]*:' distance.ld | tail -3)"
grep -q '^portalVeinDistanceMm = 4$' "$params" || fail "VesselProximityDistance: $(cat "$params")"
for program in VesselProximityModels VesselProximityTrack; do
  LD_DEBUG=libs "$cli/$program" --xml > "$program.xml" 2> "$program.ld" || fail "$program --xml"
  grep -q "<documentation-url>file://$moved/share/doc/VesselProximity/README.md</documentation-url>" "$program.xml" \
    || fail "$program: the documentation link is not the installed README: $(grep documentation-url "$program.xml")"
done
for log in phantom.ld distance.ld VesselProximityModels.ld VesselProximityTrack.ld; do
  from_build=$(grep "calling init" "$log" | grep -F "$build/" | grep -vF "$work/" || true)
  [ -z "$from_build" ] || fail "${log%.ld} loaded a library from the build tree: $(echo "$from_build" | head -1)"
  grep -F "calling init: $slicer/" "$log" | grep -q "qt-loadable-modules/libVesselProximityLogic.so" \
    || fail "${log%.ld} did not load the installed logic library"
done

# A C++ project finds the package in the moved prefix and links the logic.
cmake -S "$consumer" -B "$work/consumer" -DCMAKE_PREFIX_PATH="$moved" -DCMAKE_BUILD_TYPE=Release > "$work/consumer.log" 2>&1 \
  || fail "consumer configure: $(tail -5 "$work/consumer.log")"
cmake --build "$work/consumer" >> "$work/consumer.log" 2>&1 || fail "consumer build: $(tail -5 "$work/consumer.log")"
"$work/consumer/consumer" || fail "consumer: wrong answer"
echo "InstalledTree: installed, moved, run from elsewhere, consumed"
rm -rf "$work"
