set terminal pngcairo size 1200,450 font ',10'
set output 'table_size.png'
set multiplot layout 1,2 title 'Table size and lookup'
set grid
set logscale x 2
set xlabel 'table entries N'
set ylabel 'PSNR (dB)'
set key bottom right
set title 'against the truth (the algorithm)'
plot 'table_size.dat' index 0 using 1:2 with linespoints title 'ml41-sharp nearest', 'table_size.dat' index 1 using 1:2 with linespoints title 'ml41-ramp nearest', 'table_size.dat' index 2 using 1:2 with linespoints title 'ml41-sharp bilinear', 'table_size.dat' index 3 using 1:2 with linespoints title 'ml41-ramp bilinear'
set title 'against the reference (fixed point)'
plot 'table_size.dat' index 4 using 1:2 with linespoints title 'ml41-sharp nearest', 'table_size.dat' index 5 using 1:2 with linespoints title 'ml41-ramp nearest', 'table_size.dat' index 6 using 1:2 with linespoints title 'ml41-sharp bilinear', 'table_size.dat' index 7 using 1:2 with linespoints title 'ml41-ramp bilinear'
unset multiplot
