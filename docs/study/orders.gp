set terminal pngcairo size 1200,450 font ',10'
set output 'orders.png'
set title 'The orders against the ground truth, smooth and sharp transfer functions (higher is better)'
set style data histogram
set style histogram clustered gap 1
set style fill solid 0.8 border -1
set grid ytics
set ylabel 'PSNR against the truth (dB)'
set key top left
set xtics rotate by -20
set yrange [0:*]
plot 'orders.dat' using 2:xtic(1) title columnheader, 'orders.dat' using 3:xtic(1) title columnheader, 'orders.dat' using 4:xtic(1) title columnheader
