set terminal pngcairo size 1200,480 font ',10'
set output 'rays.png'
set multiplot layout 1,2 title 'Marschner-Lobb 41^3, sharp, 512x512, view 30,20: rays per voxel column (one slab per slice throughout)'
set grid
set logscale x 2
set xtics (1, 2, 4, 8, 16)
set xrange [0.8:20]
set xlabel 'rays per voxel column along each axis (R; R = 8 is about one ray per output pixel)'
set key bottom right
set title 'distance from the truth, 1024 table entries (higher is closer)'
set ylabel 'PSNR against the truth (dB)'
set key top left maxrows 3
set offsets 0, 0, 3, 0
plot 'rays.dat' index 0 using 1:2 with linespoints lw 2 pt 5 dashtype 1 lc 1 title 'point, partial slabs', 'rays.dat' index 1 using 1:2 with linespoints lw 2 pt 7 dashtype 2 lc 1 title 'point, whole slabs', 'rays.dat' index 2 using 1:2 with linespoints lw 2 pt 5 dashtype 1 lc 2 title 'preint1, partial slabs', 'rays.dat' index 3 using 1:2 with linespoints lw 2 pt 7 dashtype 2 lc 2 title 'preint1, whole slabs', 'rays.dat' index 4 using 1:2 with linespoints lw 2 pt 5 dashtype 1 lc 3 title 'preclass, partial slabs', 'rays.dat' index 5 using 1:2 with linespoints lw 2 pt 7 dashtype 2 lc 3 title 'preclass, whole slabs'
set title 'preint1 closer to the truth than point by'
set ylabel 'dB'
set key bottom right maxrows 5
set offsets 0, 0, 0, 0
plot 'rays.dat' index 6 using 1:2 with linespoints lw 2 pt 5 dashtype 1 lc 2 title '1024 entries, partial slabs', 'rays.dat' index 7 using 1:2 with linespoints lw 2 pt 7 dashtype 2 lc 2 title '1024 entries, whole slabs', 'rays.dat' index 8 using 1:2 with linespoints lw 2 pt 5 dashtype 1 lc 4 title '256 entries, partial slabs', 'rays.dat' index 9 using 1:2 with linespoints lw 2 pt 7 dashtype 2 lc 4 title '256 entries, whole slabs', 6 with lines dashtype 3 lc rgb 'black' title 'the claim: 6 dB'
unset multiplot
