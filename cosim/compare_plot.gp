# One scenario of the closed-loop comparison (docs/sil.md#compare): the
# real-time plant and the multibody reference, each with the example
# controller, overlaid on a shared time axis [s].
#   gnuplot -e "csv='OUT/compare-kick-down.csv'; png='kick-down.png'; name='kick-down'; slip_limit=0.10" \
#     cosim/compare_plot.gp
# Columns: cvtplant-sil compare's overlay (t, set-point, demand, then each
# trace on the plant and on the reference: ratio 4/5, slip 6/7, clamp
# command 8/9, axial force 10/11, driven command 12/13, driven axial force
# 14/15, omega1 16/17, omega2 18/19, torque 20/21, safety factor 22/23).
if (!exists("csv")) csv = "compare-tip-in.csv"
if (!exists("png")) png = "compare-tip-in.png"
if (!exists("name")) name = "tip-in"
if (!exists("slip_limit")) slip_limit = 0.10
set terminal pngcairo size 1100,1250 font ",10" noenhanced
set output png
set datafile separator ","
set grid
set key outside right top
set lmargin 12
set rmargin 34
set multiplot layout 5,1 title "cvtplant SIL compare: ".name.", example controller, lock-step; plant (solid) against the multibody reference (dashed)"
set format x ""
set ylabel "ratio [-]"
plot csv using 1:($2 > 0 ? $2 : NaN) skip 1 with steps lc "black" title "set-point", \
     csv using 1:4 skip 1 with lines lw 1.5 lc 1 title "plant geometric ratio", \
     csv using 1:5 skip 1 with lines lw 1.5 dt 2 lc 2 title "reference geometric ratio"
set ylabel "slip [-]"
plot csv using 1:6 skip 1 with lines lc 1 title "plant slip", \
     csv using 1:7 skip 1 with lines dt 2 lc 2 title "reference slip", \
     slip_limit with lines dt 3 lc "red" title sprintf("limit +/-%.2f", slip_limit), -slip_limit with lines dt 3 lc "red" notitle
set ylabel "clamping [kN]"
set yrange [0:*]
plot csv using 1:($8/1000) skip 1 with lines lc 1 title "plant: driver command", \
     csv using 1:($10/1000) skip 1 with lines lc 3 title "plant: driver axial force", \
     csv using 1:($9/1000) skip 1 with lines dt 2 lc 2 title "reference: driver command", \
     csv using 1:($11/1000) skip 1 with lines dt 2 lc 4 title "reference: driver axial force"
set autoscale y
set ylabel "speed [rad/s]"
plot csv using 1:16 skip 1 with lines lc 1 title "plant omega1", \
     csv using 1:18 skip 1 with lines lc 3 title "plant omega2", \
     csv using 1:17 skip 1 with lines dt 2 lc 2 title "reference omega1", \
     csv using 1:19 skip 1 with lines dt 2 lc 4 title "reference omega2"
set format x "%g"
set xlabel "time [s]"
set ylabel "safety factor [-]"
set yrange [0:4]
plot csv using 1:22 skip 1 with lines lc 1 title "plant", \
     csv using 1:23 skip 1 with lines dt 2 lc 2 title "reference", \
     1.05 with lines dt 3 lc "red" title "gross-slip limit 1.05"
unset multiplot
