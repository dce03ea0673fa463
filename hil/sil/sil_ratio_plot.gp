# One ratio scenario's run as a figure (docs/sil.md#plot): command, response
# and limits against time, stacked panels sharing the time axis.
#   gnuplot -e "csv='OUT/sil-ratio-sweep.csv'; png='OUT/sil-ratio-sweep.png'; name='ratio-sweep'" \
#     hil/sil/sil_ratio_plot.gp
# Columns: cvtplant-sil's trace (docs/sil.md#scenarios). The end stops are
# the ratio-control scene's (docs/sil.md#ratio-scenarios): 2.65 and 0.89.
if (!exists("csv")) csv = "sil-ratio-sweep.csv"
if (!exists("png")) png = "sil-ratio-sweep.png"
if (!exists("name")) name = "ratio-sweep"
if (!exists("how")) how = "lock-step, 10 ms control period, 1 ms plant frames"
set terminal pngcairo size 1100,1000 font ",10" noenhanced
set output png
set datafile separator ","
set grid
set key outside right top
set lmargin 12
set rmargin 30
set multiplot layout 4,1 title "cvtplant SIL: ".name." on scene ratio-control, example controller (".how.")"
set format x ""
set ylabel "ratio [-]"
plot csv using 1:12 skip 1 with steps lw 1.5 title "set-point (command)", \
     csv using 1:13 skip 1 with lines lw 1.5 title "geometric ratio (response)", \
     2.65 with lines dt 2 lc "red" title "end stops 2.65 / 0.89", 0.89 with lines dt 2 lc "red" notitle
set ylabel "slip [-]"
set yrange [-0.15:0.15]
plot csv using 1:6 skip 1 with lines title "slip", \
     0.10 with lines dt 2 lc "red" title "limit +/-0.10", -0.10 with lines dt 2 lc "red" notitle
set ylabel "clamping force [kN]"
set yrange [0:*]
plot csv using 1:($3/1000) skip 1 with lines title "driver command", \
     csv using 1:($4/1000) skip 1 with lines title "driver axial force", \
     csv using 1:($14/1000) skip 1 with lines title "driven command", \
     csv using 1:($15/1000) skip 1 with lines title "driven axial force"
set format x "%g"
set xlabel "time [s]"
set ylabel "safety factor [-]"
set yrange [0:4]
plot csv using 1:9 skip 1 with lines title "torque capacity / |torque|", \
     1.05 with lines dt 2 lc "red" title "gross-slip limit 1.05"
unset multiplot
