#!/bin/bash
# Run on the GPU machine from the checkout root, through the pack: bash .gpu/run.sh bash
# Benchmark/Device/MeasureBatchPasses.sh (../shared/gpu/README.md). $OUT gets the JSON report, its
# table and nvidia-smi's clock samples.
# Issue 35's batch rate: 20,000 tips at 1.5M triangles per class (IRCADb patient 1's vessels,
# refined), the batch through each query pass and each listing pass side by side (batch_passes:
# a workgroup or an invocation listing each answer's tiles), where its time goes (the device's by
# stage: listing, visiting, reducing; host wait, inside votes, ceilings, answers read), with one
# submission in flight and with two (batch_in_flight: the host's work beside the device's), its
# tips as given and in space order (batch_order: neighbouring invocations on neighbouring tiles),
# beside the single tip and the exact engine on the host's cores.
set -u
source Benchmark/Device/RecordMachine.sh
v=portal_vein=.gpu/ircadb/portalvein.vtk,hepatic_artery=.gpu/ircadb/artery.vtk,hepatic_vein=.gpu/ircadb/venoussystem.vtk
timeout 400 $VP bench --engines zbuffer --sizes 1500000 --queries 20000 --brute-queries 3 --vessels $v \
  -o "$out/batch.json" > "$out/batch.txt" 2>&1
echo "bench rc=$?" >> "$out/batch.txt"
stop_recording
tail -n 30 "$out/batch.txt"
