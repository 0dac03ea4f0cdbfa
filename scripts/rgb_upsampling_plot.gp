# Spectra of a few sRGB colours under the two upsampling models (docs/rgb-upsampling.md):
# Jakob & Hanika's sigmoid polynomials (solid) and the logistic basis (dashed).
#   g++ -std=c++20 -O2 -fno-math-errno -fno-trapping-math -I include scripts/rgb2spec_measure.cpp -o /tmp/rgb2spec_measure
#   /tmp/rgb2spec_measure --plot-data /tmp/rgb-upsampling.dat
#   gnuplot -e "data='/tmp/rgb-upsampling.dat'" scripts/rgb_upsampling_plot.gp   # writes docs/rgb-upsampling.png
if (!exists("data")) data = '/tmp/rgb-upsampling.dat'
set terminal pngcairo size 1100,560 font ",11"
set output 'docs/rgb-upsampling.png'
set title "sRGB → reflectance: Jakob and Hanika 2019 (solid) vs the logistic basis (dashed), under D65"
set xlabel "wavelength (nm)"
set ylabel "reflectance"
set xrange [360:830]
set yrange [-0.02:1.05]
set grid
set key outside right top
names = "red green blue yellow pastel-pink skin"
colours = "#d62728 #2ca02c #1f77b4 #bcbd22 #e377c2 #8c564b"
plot for [i=1:6] data using 1:(column(2*i)) with lines lw 2 lc rgb word(colours, i) title word(names, i)." JH", \
     for [i=1:6] data using 1:(column(2*i+1)) with lines lw 2 dt 2 lc rgb word(colours, i) title word(names, i)." logistic"
