// generated from config/configs.json by cmake/ShadecoreConfigs.cmake — do not edit
// Values of the VARIANT parameter of rtl/sc_specular.v (included inside the module).
localparam integer VARIANT_CS16 = 0;
localparam integer VARIANT_SCHLICK_DIV = 1;
localparam integer VARIANT_SCHLICK_NR = 2;
localparam integer VARIANT_SCHLICK_ITER = 3;
localparam integer VARIANT_TABLE256 = 6;
localparam integer VARIANT_TABLE256_ENTRIES = 256;
localparam integer VARIANT_TABLE1024 = 7;
localparam integer VARIANT_TABLE1024_ENTRIES = 1024;
