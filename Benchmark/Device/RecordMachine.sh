# Sourced by the device scripts (Benchmark/Device/Measure*.sh) before they measure: $out is
# $OUT (where the device tool collects files) or /tmp/out; the GPU and the host's CPU are named
# in gpu.txt and cpu.txt, and nvidia-smi samples the SM clock into smi.csv every 250 ms (a GPU's
# clock follows its load: the samples tell at what clock a number was taken) until the script
# calls stop_recording.
out=${OUT:-/tmp/out}
mkdir -p "$out"
nvidia-smi --query-gpu=timestamp,clocks.sm,utilization.gpu --format=csv -lms 250 > "$out/smi.csv" 2>/dev/null &
smi=$!
nvidia-smi -L > "$out/gpu.txt" 2>&1
lscpu | head -20 > "$out/cpu.txt"
stop_recording() { kill "$smi"; }
