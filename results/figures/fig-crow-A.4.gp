# Crow 1976 fig. A.4 as a measurement: made by aabench figures; run with: gnuplot fig-crow-A.4.gp
set terminal pngcairo size 1100,460 font 'DejaVu Sans,10'
if (!exists('out')) out = 'fig-crow-A.4.png'
if (!exists('dat')) dat = 'fig-crow-A.4.dat'
set output out
set multiplot layout 1,2
set grid
set title 'Grey scale on a square-law monitor (fig. A.4: readings and square roots)'
set xlabel 'stored value v (linear grey scale)'
set ylabel 'shown intensity (solid) and its square root (dashed)'
set key top left
plot dat index 0 using 1:2 with lines lw 2 lc 1 title 'A.1 linear map: v^2', \
     '' index 0 using 1:3 with lines lw 2 lc 2 title 'A.2 convex upward: v', \
     '' index 0 using 1:4 with lines lw 2 lc 3 title 'A.3 concave upward: v^4', \
     '' index 0 using 1:5 with lines dt 2 lc 1 notitle, \
     '' index 0 using 1:6 with lines dt 2 lc 2 notitle, \
     '' index 0 using 1:7 with lines dt 2 lc 3 notitle
set title 'Moire seen by an eye of s = 2 dots, pattern under the two-dot pyramid'
set xlabel 'display response exponent g (shown intensity v^g)'
set ylabel 'error the eye sees (linear light)'
set key bottom right
set arrow from 1,graph 0 to 1,graph 1 nohead dt 3 lc 2
set arrow from 2,graph 0 to 2,graph 1 nohead dt 3 lc 1
set arrow from 4,graph 0 to 4,graph 1 nohead dt 3 lc 3
set label 'A.2' at 1.03,graph 0.95
set label 'A.1 (Crow)' at 2.03,graph 0.95
set label 'A.3' at 3.75,graph 0.95
plot dat index 1 using 1:2 with lines lw 2 lc 4 title 'fringes, crowtable', \
     '' index 1 using 1:3 with lines lw 1 dt 2 lc 4 title 'fringes, exact', \
     '' index 1 using 1:4 with lines lw 2 lc 7 title 'eye rmse, crowtable', \
     '' index 1 using 1:5 with lines lw 1 dt 2 lc 7 title 'eye rmse, exact'
unset multiplot
