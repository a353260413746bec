#!/bin/bash
# ab.sh NAME EXTRA_STRAIN PAIRS: shifted IC(0) (default) against ic_shifts [] (the fallback before), in turns, one thread
name=$1; extra=$2; pairs=${3:-3}
root=$(cd "$(dirname "$0")/../.." && pwd); here=$(cd "$(dirname "$0")" && pwd); out=${OUT:-/tmp/solver_probe}
ck=$root/results/sensitivity/$name.h5.checkpoint
t=$(h5dump -d /strain $ck | grep -o "(0): [0-9.e+-]*" | awk '{print $2}')
dur=$(/usr/bin/python3 -c "print($t+$extra)")
for p in $(seq $pairs); do for v in shift none; do
  d=$out/ab-$name-$v-$p; rm -rf $d; mkdir -p $d; if [ $v = none ]; then /usr/bin/python3 $here/noshift_ckpt.py $ck $d/c.h5.checkpoint; else cp $ck $d/c.h5.checkpoint; fi
  set_arg=""; [ $v = none ] && set_arg="--set hydro.ic_shifts=[]"
  (cd $root && OMP_NUM_THREADS=1 build/bin/fldsim run examples/paper/sensitivity/$name.yaml --set output=$d/c.h5 --set run.duration=$dur $set_arg --resume $d/c.h5.checkpoint > $d/log 2>&1)
  echo "$name $v $p: $(grep -o 'done: .*CG iterations/step' $d/log) | $(grep -o 'broken down [0-9]* times: .*' $d/log | tail -1)"
done; done
