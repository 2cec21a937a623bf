set terminal pngcairo size 1200,900 font ',10'
set output 'bits.png'
set multiplot layout 2,2 title 'Fixed-point error by precision of each stage (PSNR against the double reference, higher is better)'
set grid
set key bottom right
set ylabel 'PSNR (dB)'
set xlabel 'table entries (bits)'
set yrange [20:100]
plot 'bits.dat' index 0 using 1:2 with linespoints title 'ml41-sharp', 'bits.dat' index 1 using 1:2 with linespoints title 'ml41-ramp', 'bits.dat' index 2 using 1:2 with linespoints title 'neghip-sharp', 'bits.dat' index 3 using 1:2 with linespoints title 'neghip-mr-brain', 'bits.dat' index 4 using 1:2 with linespoints title 'brain-mr-brain', 'bits.dat' index 5 using 1:2 with linespoints title 'engine-ct-bone', 'bits.dat' index 6 using 1:2 with linespoints title 'engine-ramp', 'bits.dat' index 7 using 1:2 with linespoints title 'cthead-ct-skin-bone', 'bits.dat' index 8 using 1:2 with linespoints title 'headsq-ct-bone', 'bits.dat' index 9 using 1:2 with linespoints title 'bucky-sharp'
set xlabel 'samples (fraction bits; 32 = exact)'
set yrange [20:100]
plot 'bits.dat' index 10 using 1:2 with linespoints title 'ml41-sharp', 'bits.dat' index 11 using 1:2 with linespoints title 'ml41-ramp', 'bits.dat' index 12 using 1:2 with linespoints title 'neghip-sharp', 'bits.dat' index 13 using 1:2 with linespoints title 'neghip-mr-brain', 'bits.dat' index 14 using 1:2 with linespoints title 'brain-mr-brain', 'bits.dat' index 15 using 1:2 with linespoints title 'engine-ct-bone', 'bits.dat' index 16 using 1:2 with linespoints title 'engine-ramp', 'bits.dat' index 17 using 1:2 with linespoints title 'cthead-ct-skin-bone', 'bits.dat' index 18 using 1:2 with linespoints title 'headsq-ct-bone', 'bits.dat' index 19 using 1:2 with linespoints title 'bucky-sharp'
set xlabel 'intermediate image (bits)'
set yrange [20:100]
plot 'bits.dat' index 20 using 1:2 with linespoints title 'ml41-sharp', 'bits.dat' index 21 using 1:2 with linespoints title 'ml41-ramp', 'bits.dat' index 22 using 1:2 with linespoints title 'neghip-sharp', 'bits.dat' index 23 using 1:2 with linespoints title 'neghip-mr-brain', 'bits.dat' index 24 using 1:2 with linespoints title 'brain-mr-brain', 'bits.dat' index 25 using 1:2 with linespoints title 'engine-ct-bone', 'bits.dat' index 26 using 1:2 with linespoints title 'engine-ramp', 'bits.dat' index 27 using 1:2 with linespoints title 'cthead-ct-skin-bone', 'bits.dat' index 28 using 1:2 with linespoints title 'headsq-ct-bone', 'bits.dat' index 29 using 1:2 with linespoints title 'bucky-sharp'
set xlabel 'warp weights (fraction bits)'
set yrange [20:100]
plot 'bits.dat' index 30 using 1:2 with linespoints title 'ml41-sharp', 'bits.dat' index 31 using 1:2 with linespoints title 'ml41-ramp', 'bits.dat' index 32 using 1:2 with linespoints title 'neghip-sharp', 'bits.dat' index 33 using 1:2 with linespoints title 'neghip-mr-brain', 'bits.dat' index 34 using 1:2 with linespoints title 'brain-mr-brain', 'bits.dat' index 35 using 1:2 with linespoints title 'engine-ct-bone', 'bits.dat' index 36 using 1:2 with linespoints title 'engine-ramp', 'bits.dat' index 37 using 1:2 with linespoints title 'cthead-ct-skin-bone', 'bits.dat' index 38 using 1:2 with linespoints title 'headsq-ct-bone', 'bits.dat' index 39 using 1:2 with linespoints title 'bucky-sharp'
unset multiplot
