set terminal pngcairo size 1200,450 font ',10'
set output 'peaks.png'
set multiplot layout 1,2 title 'Marschner-Lobb 41^3, three opacity peaks of varying width'
set grid
set xlabel 'half-width of each peak (fraction of the window)'
set key bottom right
set title 'against the truth'
set ylabel 'PSNR (dB)'
plot 'peaks.dat' index 0 using 1:2 with linespoints title 'point, whole view', '' index 0 using 1:3 with linespoints title 'preint1, whole view', '' index 1 using 1:2 with linespoints title 'point, interior', '' index 1 using 1:3 with linespoints title 'preint1, interior'
set title 'preint1 closer than point by'
set ylabel 'dB'
plot 'peaks.dat' index 0 using 1:4 with linespoints title 'whole view', '' index 1 using 1:4 with linespoints title 'interior', 6 with lines dashtype 2 title '6 dB'
unset multiplot
