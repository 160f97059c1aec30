#!/bin/bash
# Run on the GPU machine from the checkout root, through the pack: bash .gpu/run.sh bash
# Benchmark/Device/MeasurePenetrationAndZBuffer.sh (../shared/gpu/README.md). $OUT, where the device
# tool collects files, gets the JSON reports and nvidia-smi's clock samples.
# Issue 35's GPU measurements, one script: the penetration sweep (exact and z-buffer through the
# logic, FCL's primitives) twice (100 and 400 poses), with nvidia-smi sampling the SM clock, then
# the single tip from 150k to 4.5M triangles and the batch rate, bounded in time.
set -u
source Benchmark/Device/RecordMachine.sh
$VP bench --engines penetration -o "$out/penetration100.json" > "$out/penetration100.txt" 2>&1
$VP bench --engines penetration --penetration-poses 400 -o "$out/penetration400.json" > "$out/penetration400.txt" 2>&1
timeout 300 $VP bench --engines zbuffer --sizes 150000,4500000 --queries 500 --brute-queries 5 --vessels portal_vein=.gpu/ircadb/portalvein.vtk,hepatic_artery=.gpu/ircadb/artery.vtk,hepatic_vein=.gpu/ircadb/venoussystem.vtk -o "$out/zbuffer.json" > "$out/zbuffer.txt" 2>&1
echo "zbuffer rc=$?" >> "$out/zbuffer.txt"
stop_recording
tail -n 30 "$out/penetration100.txt" "$out/penetration400.txt"; tail -n 40 "$out/zbuffer.txt"
