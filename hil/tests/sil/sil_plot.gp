# Summary plot of the SIL scenarios (docs/sil.md#plot):
#   gnuplot -e "dir='OUT'" hil/tests/sil/sil_plot.gp   ->  OUT/sil-summary.png
# One column per scenario: slip, torque-capacity safety factor, clamping.
if (!exists("dir")) dir = "."
set terminal pngcairo size 1500,900 font ",9" noenhanced
set output dir."/sil-summary.png"
set datafile separator ","
set key top right
set grid
set multiplot layout 3,3 title "cvtplant SIL: example controller vs bridge (lock-step over vcan0)"
do for [s in "tip-in load-step clamp-loss"] {
  f = dir."/sil-".s.".csv"
  set title s." : slip"
  set yrange [-0.12:0.12]
  plot f using 1:6 skip 1 with lines title "slip", 0.10 with lines dt 2 lc "red" title "limit", -0.10 with lines dt 2 lc "red" notitle
}
do for [s in "tip-in load-step clamp-loss"] {
  f = dir."/sil-".s.".csv"
  set title s." : safety factor tau_cap/|tau|"
  set yrange [0:5]
  plot f using 1:9 skip 1 with lines title "SF", 1.05 with lines dt 2 lc "red" title "gross-slip limit"
}
do for [s in "tip-in load-step clamp-loss"] {
  f = dir."/sil-".s.".csv"
  set title s." : clamping [kN], torque [10 N m]"
  set yrange [*:*]
  plot f using 1:($3/1000) skip 1 with lines title "command", \
       f using 1:($4/1000) skip 1 with lines title "axial force", \
       f using 1:($5/10) skip 1 with lines title "torque/10", \
       f using 1:($10*5) skip 1 with steps title "cmd timeout"
}
unset multiplot
